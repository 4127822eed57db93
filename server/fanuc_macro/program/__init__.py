"""The program model: the index of programs, labels, loops and calls, what variable numbers
are, what comments say a variable means, what codes mean (see ARCHITECTURE.md)."""
