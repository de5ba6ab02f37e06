#include "solve_option_json.h"

#include "http_error.h"
#include "json_input.h"

#include "iarap/solver/solve_option_fields.h"

namespace iarap::serve {

std::vector<std::string> solve_option_names() {
  const ArapSolveOptions library_defaults;
  std::vector<std::string> names;
  visit_solve_option_fields(library_defaults, [&names](const SolveOptionField& field, const auto&) {
    names.push_back(field.name);
  });
  return names;
}

void read_solve_options(const nlohmann::json& body, ArapSolveOptions& options) {
  visit_solve_option_fields(options, [&](const SolveOptionField& field, const auto&) {
    const auto it = body.find(field.name);
    if (it == body.end()) return;
    // A number goes as its JSON text through the library's parser (one message for every front-end; its
    // InputError answers 400); a string is a choice's name, never a number.
    const bool choice = field.kind == SolveOptionKind::Choice;
    if (choice ? !it->is_string() : !it->is_number())
      throw HttpError(400, solve_option_error(field, short_description(*it)));
    set_solve_option(options, field.name, choice ? it->get<std::string>() : it->dump());
  });
}

} // namespace iarap::serve
