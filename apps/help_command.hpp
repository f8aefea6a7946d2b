// `swell help case [KEY.PATH]`: the case-file reference (Markdown), generated from the schema
// (case/schema.hpp): every key, or one key or section.
#pragma once

#include "apps/subcommand.hpp"

namespace swell {

Subcommand add_help_command(CLI::App& app);

}  // namespace swell
