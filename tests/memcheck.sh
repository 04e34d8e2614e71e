#!/bin/sh
# Runs ffsim under valgrind memcheck: memcheck.sh VALGRIND FFSIM ARGS...
# Exit 9: memcheck found an error; otherwise ffsim's own exit code.
#
# Exit 77 (CTest: "Skipped", SKIP_RETURN_CODE) only when valgrind cannot even
# start ffsim on this machine because a *system library* executes an
# instruction valgrind does not decode. Seen on AMD EPYC (Zen 4) virtual
# machines with valgrind 3.19: libhwy (OpenImageIO -> libjxl -> libhwy) runs
# RDTSCP in its load-time initialiser while the CPUID the hypervisor reports
# hides RDTSCP, so valgrind refuses the instruction and kills the process
# before main. A failure at an address inside ffsim itself is never skipped.
valgrind=$1; shift
ffsim=$1; shift
if ! probe=$("$valgrind" "$ffsim" --version 2>&1); then
  if printf '%s\n' "$probe" | grep -q "unhandled instruction bytes"; then
    where=$(printf '%s\n' "$probe" | grep -m1 -E '^==[0-9]+== +at ')
    case "$where" in
      *"(in /lib/"*|*"(in /usr/lib/"*)
        bytes=$(printf '%s\n' "$probe" | grep -m1 "unhandled instruction bytes")
        echo "SKIPPED: $("$valgrind" --version) cannot start ffsim on this CPU:"
        echo "  $bytes"
        echo "  $where"
        echo "  (a system library's start-up code, before ffsim's main; see tests/memcheck.sh)"
        exit 77;;
    esac
  fi
  echo "valgrind could not run '$ffsim --version':"
  printf '%s\n' "$probe"
  exit 1
fi
exec "$valgrind" --error-exitcode=9 -q "$ffsim" "$@"
