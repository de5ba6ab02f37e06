#include "solve_option_flags.h"

#include "iarap/core/errors.h"
#include "iarap/solver/solve_option_fields.h"

#include <string>

namespace iarap::cli {

void add_solve_option_flags(CLI::App& command, ArapSolveOptions& options) {
  visit_solve_option_fields(options, [&](const SolveOptionField& field, const auto& value) {
    const std::string name = field.name;
    // The range goes in the help text; a refused value is reported by the library's own message.
    const CLI::Validator in_range(
        [name](std::string& text) -> std::string {
          ArapSolveOptions scratch;
          try {
            set_solve_option(scratch, name, text);
          } catch (const InputError& e) {
            return e.what();
          }
          return {};
        },
        "");
    const char* kind = field.kind == SolveOptionKind::Integer  ? "INT:"
                       : field.kind == SolveOptionKind::Number ? "FLOAT:"
                                                               : "NAME:";
    command
        .add_option(
            field.flag,
            [&options, name](const CLI::results_t& results) {
              set_solve_option(options, name, results.front());
              return true;
            },
            std::string(field.doc) + (*field.unit ? std::string(" (") + field.unit + ")" : std::string()))
        ->type_name(kind + solve_option_range(field)) // "--window INT:an integer in [0, 1000]=8"
        ->default_str(solve_option_value_text(value))
        ->check(in_range);
  });
}

} // namespace iarap::cli
