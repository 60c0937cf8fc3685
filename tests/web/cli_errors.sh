#!/usr/bin/env bash
# web.cli_errors: bad `--web…` input exits 2 with a message naming the option and the allowed values, and leaves no
# session folder behind. Usage: cli_errors.sh FREEPLAY SCENARIO WORKDIR
set -uo pipefail
freeplay=$1 scenario=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
failures=0
expect() {  # expect MESSAGE ARGS…: exit status 2, MESSAGE on stderr, no session folder
  local message=$1; shift
  "$freeplay" serve "$scenario" --web-out "$work/session" "$@" >"$work/out" 2>"$work/err"
  local rc=$?
  if [ $rc -ne 2 ] || ! grep -qF -- "$message" "$work/err" || [ -e "$work/session" ]; then
    echo "FAIL: serve $* → exit $rc, stderr: $(cat "$work/err")"; failures=$((failures + 1))
  else
    echo "ok   serve $* → exit 2: $(head -1 "$work/err")"
  fi
}
expect "'abc' is not a port" --web abc
expect "is not a port" --web 127.0.0.1:70000
expect "serving beyond loopback needs an access token" --web 0.0.0.0:0
expect "shorter than 16 characters" --web 0.0.0.0:0 --web-token short
expect "'1.2.3' is not an IP address" --web 1.2.3:0 --web-token 0123456789abcdef
expect "cannot take --robot external" --web 0 --robot external
expect "not in {autonomous,wizard,supervised}" --web 0 --web-mode boss
# A port in use: the second server refuses and writes nothing.
python3 -c 'import socket,time,sys; s=socket.socket(); s.bind(("127.0.0.1",0)); s.listen(); print(s.getsockname()[1], flush=True); time.sleep(30)' >"$work/port" &
holder=$!
for _ in $(seq 50); do [ -s "$work/port" ] && break; sleep 0.1; done
expect "cannot listen on 127.0.0.1:$(cat "$work/port")" --web "$(cat "$work/port")"
kill "$holder"
exit $((failures > 0))
