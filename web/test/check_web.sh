#!/usr/bin/env bash
# make check-web: serves the built site (make serve), waits for it, runs the browser tests
# (web/test/browser.mjs) and stops the server whatever happens.
set -euo pipefail
port=${WEB_PORT:-8457}
url=http://127.0.0.1:$port/
log=$(mktemp)
make --no-print-directory serve WEB_PORT="$port" >"$log" 2>&1 &
server=$!
stop() { kill "$server" 2>/dev/null; pkill -P "$server" 2>/dev/null || true; wait "$server" 2>/dev/null || true; rm -f "$log"; }
trap stop EXIT
for _ in $(seq 100); do
  if node -e "fetch('$url').then(r => process.exit(r.ok ? 0 : 1), () => process.exit(1))"; then break; fi
  if ! kill -0 "$server" 2>/dev/null; then echo "check-web: make serve exited:" >&2; cat "$log" >&2; exit 1; fi
  sleep 0.2
done
node -e "fetch('$url').then(r => process.exit(r.ok ? 0 : 1), () => process.exit(1))" ||
  { echo "check-web: nothing answers at $url after 20 s; make serve said:" >&2; cat "$log" >&2; exit 1; }
echo "check-web: site at $url"
node web/test/browser.mjs "$url"
