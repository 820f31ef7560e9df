// The sanitizer runtime's defaults for the toonwater program of a sanitizer build
// (TOONWATER_SANITIZE; compiled only there). The runtime calls this hook before it reads
// ASAN_OPTIONS, which still overrides any flag it names; `ASAN_OPTIONS=help=1 toonwater`
// lists the flags with their values.
//
// intercept_tls_get_addr=0: up to GCC 13 and LLVM 16, the runtime's __tls_get_addr interceptor
// can take a dynamic TLS block of glibc 2.25 or later for one with glibc 2.19's header, when its
// address happens to lie at that header's size past a page, and LeakSanitizer then scans a
// range read from the words before it: "Tracer caught signal 11" at exit, depending on the
// memory layout. The program's modules (toonwater-images.so, toonwater-vdb.so) and the
// libraries they open have dynamic TLS; without the interceptor, LeakSanitizer leaves that TLS
// out of its roots instead of guessing its range.
extern "C" const char* __asan_default_options() { return "intercept_tls_get_addr=0"; }
