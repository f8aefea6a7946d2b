// The case-file schema: every section and key the case-file reader accepts, with its type,
// default, unit, allowed values and a one-line description (case/schema.cpp holds the table).
//
// The reader (case/reader.cpp and case/*.cpp) takes its allowed-key lists, and the forms a
// section comes in (gauge kinds, motion types, wave kinds, ...), from this table only, so a key
// cannot be accepted without an entry here. The reference (`swell help case`,
// docs/case_reference.md) is generated from the same table; tests/test_case_reference.cpp
// checks that every entry is read by the parser and that the committed document is current.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace swell::case_schema {

using Names = std::vector<std::string_view>;

// A map of the case file. `path` names it as in error messages but with list items written
// `[]`: "physics.viscosity", "bodies[].motion", "gauges[]"; "" is the top level.
struct Section {
  std::string_view path;
  // What selects the form a key belongs to ("model", "kind", "type", "dim"), and the forms in
  // the order the reader lists them; empty when the section has one form. A form may have
  // sub-forms written "form:sub" (a wave motion's wave kinds: "wave:regular").
  std::string_view selector;
  std::string_view forms;        // space-separated
  std::string_view subselector;  // the key selecting sub-forms ("wave"), if any
  std::string_view description;
};

struct Key {
  std::string_view section;  // Section::path
  std::string_view name;
  // The forms of the section that take the key, space-separated; "" in every form.
  std::string_view forms;
  std::string_view type;           // number, integer, bool, name, choice, vector, map, list, ...
  std::string_view default_value;  // "required", or the value (or rule) used without the key
  std::string_view unit;           // SI, "" when dimensionless
  std::string_view allowed;        // allowed values or range; choices as "a | b | c"
  std::string_view description;
};

const std::vector<Section>& sections();
const std::vector<Key>& keys();

// The section with this path; throws std::logic_error for an unknown one (a programming error
// in the reader).
const Section& section(std::string_view path);

// Keys of a section, in table order, each name once.
//   all_keys:    every key of the section, whatever the form;
//   common_keys: the keys every form takes (Key::forms empty);
//   form_keys:   the keys of `form` itself (a form "wave" also gets its sub-forms' keys);
//   keys_for:    common_keys followed by form_keys: what a map of that form may hold.
Names all_keys(std::string_view section);
Names common_keys(std::string_view section);
Names form_keys(std::string_view section, std::string_view form);
Names keys_for(std::string_view section, std::string_view form);
// The forms of a section (Section::forms split); with `parent` ("wave"), the sub-forms of that
// form without the prefix ("regular", "solitary", ...).
Names forms(std::string_view section, std::string_view parent = "");
// The values of a choice key, from Key::allowed ("a | b | c"); the first entry of the key in
// the section whose allowed values are a choice list.
Names choices(std::string_view section, std::string_view key);

// The whole reference as Markdown (docs/case_reference.md is this text).
std::string reference_markdown();
// The reference entries of one key path ("physics.viscosity.alpha", "bodies[0].motion.height",
// "gauges.at"; list indices optional) or of one section ("physics.boundary"), as Markdown;
// nullopt when nothing matches.
std::optional<std::string> reference_entry(std::string_view key_path);

}  // namespace swell::case_schema
