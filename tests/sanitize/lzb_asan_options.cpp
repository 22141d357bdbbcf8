// Linked into the lzb program of the sanitizer build only (LZB_SANITIZE). Open MPI and Mesa keep
// allocations past MPI_Finalize and OSMesaDestroyContext, some made in plugins they dlclose,
// whose frames no unwinder names: the fast one stops there, so suppressions cannot match, and
// the slow one (fast_unwind_on_malloc=0) deadlocked against llvmpipe's threads. So lzb, which
// starts both, runs without leak detection; every GoogleTest program keeps it, and ASan and
// UBSan stay on in lzb too.
extern "C" const char* __asan_default_options() { return "detect_leaks=0"; }
