#pragma once
// Pieces of the text of a study's options (`--vary`, `--random`, `--metric`).

#include <string>
#include <utility>
#include <vector>

namespace lagrange::sweep {

/// `text` without leading and trailing blanks.
std::string trim(const std::string& text);

/// `text` cut at each `sep`, each piece trimmed.
std::vector<std::string> split(const std::string& text, char sep);

/// The finite number `text` writes in the model language (`0.5`, `pi/4`, no names);
/// StudyError "<context>: …" saying what is wrong otherwise.
double finite_number(const std::string& text, const std::string& context);

/// `NAME=REST` of `spec` as (NAME, REST), both trimmed; StudyError naming `option` and what was
/// expected when the '=' or the name is missing.
std::pair<std::string, std::string> name_and_value(const std::string& spec,
                                                   const std::string& option,
                                                   const std::string& expected);

}  // namespace lagrange::sweep
