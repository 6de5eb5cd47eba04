// Linked into the sanitized executable and test binary only (CMakeLists.txt, the sanitized twin):
// their sanitizer settings, so that every start — by CTest, by a test, by a user — reports the
// same way without an environment to remember. A report fails the run that triggers it, leaks
// included; a variable ASAN_OPTIONS / UBSAN_OPTIONS set by hand still overrides these.
extern "C" const char* __asan_default_options() {
  return "detect_leaks=1:abort_on_error=1:strict_string_checks=1";
}
extern "C" const char* __ubsan_default_options() { return "print_stacktrace=1:halt_on_error=1"; }
