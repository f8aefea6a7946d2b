// Anchors the swell_bench library (CMake needs one source even before the folder has any).
namespace swell {
int bench_lib_anchor = 0;
}  // namespace swell
