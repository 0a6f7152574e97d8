# What every MPI test script shares (sourced after ../lib.bash): mpirun as
# root on an oversubscribed localhost, and the MPI array to launch with.
: "${MPIEXEC:?}"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
# Under -DIL_SANITIZE=ON: Open MPI's runtime (and the plugins it unloads)
# leaks at exit, which LeakSanitizer would report as ours; illum's own
# allocations are leak-checked by every other test.
export ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0"
MPI=("$MPIEXEC" --oversubscribe)
