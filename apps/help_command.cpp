#include "apps/help_command.hpp"

#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>

#include "case/schema.hpp"

namespace swell {

Subcommand add_help_command(CLI::App& app) {
  struct Options {
    std::string topic, key;
  };
  auto o = std::make_shared<Options>();
  auto* help = app.add_subcommand(
      "help",
      "reference documentation: `swell help case` (every case-file key, Markdown) or "
      "`swell help case KEY.PATH` (one key or section)");
  help->add_option("topic", o->topic, "case")->required()->check(CLI::IsMember({"case"}));
  help->add_option("key", o->key, "a key path such as physics.coefh or gauges.band");
  return Subcommand(help, [o] {
    if (o->key.empty()) {
      std::cout << case_schema::reference_markdown();
    } else if (const auto entry = case_schema::reference_entry(o->key)) {
      std::cout << *entry;
    } else {
      std::string sections;
      for (const auto& s : case_schema::sections())
        if (!s.path.empty()) sections += (sections.empty() ? "" : ", ") + std::string(s.path);
      throw std::invalid_argument("help case: no key or section '" + o->key +
                                  "' in the case-file schema; sections: " + sections +
                                  " (and the top-level keys); `swell help case` lists them all");
    }
    return 0;
  });
}

}  // namespace swell
