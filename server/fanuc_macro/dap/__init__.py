"""The debugger's front end: the Debug Adapter Protocol over stdio (``fanuc-macro-dap``), on
the protocol-free session of :mod:`fanuc_macro.debugger`."""
