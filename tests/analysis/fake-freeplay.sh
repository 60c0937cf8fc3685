#!/bin/bash
# `freeplay` for the Slurm test while `freeplay suite` is not in this build: `suite` goes to the stand-in
# ($FREEPLAY_FAKE_SUITE, real runner with synthetic episodes), everything else to the real program ($FREEPLAY_REAL).
if [ "${1:-}" = "suite" ]; then
  if [ "${2:-}" = "--help" ]; then echo "stand-in: freeplay suite SUITE --shard I/N --out DIR"; exit 0; fi
  exec "${FREEPLAY_FAKE_SUITE:?}" "$@"
fi
exec "${FREEPLAY_REAL:?}" "$@"
