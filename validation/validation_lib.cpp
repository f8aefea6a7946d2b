// Anchors the swell_validation library (CMake needs one source even before the folder has any).
namespace swell {
int validation_lib_anchor = 0;
}  // namespace swell
