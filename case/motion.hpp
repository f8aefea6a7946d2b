// Reader of a body's `motion:` key (case/motion.cpp). Internal to the case-file reader, like
// case/parse_util.hpp; not a public API.
#pragma once

#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

#include "bc/motion.hpp"
#include "case/parse_util.hpp"

namespace swell::case_parse {

// Reads `motion: none` or a map such as {type: sinusoidal, amplitude: 0.05, period: 1.2} into a
// MotionSpec in SI units (degrees in the file become radians). A `file` is taken relative to
// `case_dir` (unless absolute) and loaded now. `reader` supplies the file label and dimension;
// `path` is the key path of the motion node ("bodies[1].motion"). `g` = |gravity| (wavemakers'
// dispersion), `dp` the particle spacing (their resolution checks). Throws CaseError.
MotionSpec read_motion(const NodeReader& reader, const YAML::Node& node, const std::string& path,
                       const std::string& case_dir, double g = 9.81, double dp = 0.0);

// The wave kinds the reader has a reader for (`wave:` of a `type: wave` motion), in its table's
// order; the schema's forms "wave:<kind>" must name the same (tests/test_motion.cpp).
std::vector<std::string> wave_kind_names();

}  // namespace swell::case_parse
