# Shared by the CLI's shell tests: `expect STATUS PATTERN -- command...` runs the command and sets fail=1 (printing
# the command, its status and its last output lines) unless it exits with STATUS and its output contains PATTERN.
expect() {
  local status=$1 pattern=$2; shift 3
  local out; out=$("$@" 2>&1); local got=$?
  if [ "$got" -ne "$status" ] || ! grep -qF -- "$pattern" <<<"$out"; then
    echo "FAIL: $* → status $got (want $status), output:"; echo "$out" | tail -5; echo "  (wanted: $pattern)"; fail=1
  fi
}
