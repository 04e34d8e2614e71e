#!/bin/sh
# Runs ffsim under valgrind memcheck: memcheck.sh VALGRIND SHIM FFSIM ARGS...
# Exit 9: memcheck found an error; otherwise ffsim's own exit code.
#
# Some machines need SHIM (tests/valgrind_hwy_timer_shim.cpp): valgrind 3.19
# on AMD EPYC (Zen 4) virtual machines cannot start ffsim, because libhwy
# (OpenImageIO -> libjxl -> libhwy) runs RDTSCP in its load-time initialiser
# while the CPUID the hypervisor reports hides RDTSCP; valgrind refuses the
# instruction and kills the process before main. When `ffsim --version` fails
# that way, the run preloads the shim, which replaces that initialiser's timer.
# Exit 77 (CTest: "Skipped", SKIP_RETURN_CODE) only when valgrind still cannot
# start ffsim because of an instruction inside a system library. A failure at
# an address inside ffsim itself is never skipped.
valgrind=$1; shift
shim=$1; shift
ffsim=$1; shift
if ! probe=$("$valgrind" "$ffsim" --version 2>&1); then
  if printf '%s\n' "$probe" | grep -q "hwy::platform::TimerResolution" &&
     LD_PRELOAD="$shim" "$valgrind" -q "$ffsim" --version > /dev/null 2>&1; then
    echo "memcheck.sh: valgrind cannot run libhwy's RDTSCP timer set-up here; preloading $shim"
    LD_PRELOAD="$shim"
    export LD_PRELOAD
  elif printf '%s\n' "$probe" | grep -q "unhandled instruction bytes"; then
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
    echo "valgrind could not run '$ffsim --version':"
    printf '%s\n' "$probe"
    exit 1
  else
    echo "valgrind could not run '$ffsim --version':"
    printf '%s\n' "$probe"
    exit 1
  fi
fi
exec "$valgrind" --error-exitcode=9 -q "$ffsim" "$@"
