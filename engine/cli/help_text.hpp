#pragma once
// What the command line says about itself, generated from the table of
// engine/cli/command_definitions.cpp: the top-level usage, each command's help, the bash
// completion script (completion_script.cpp) and the man page (man_page.cpp).
#include <string>
#include <string_view>

#include "engine/cli/command_definitions.hpp"

namespace hapscene {

// `hapscene help`, `hapscene --help`: every command, its forms and their options.
std::string top_level_usage();

// `hapscene CMD --help`, `hapscene help CMD`: usage, description, options with their
// defaults, units and ranges, and examples, for every form of the command. Empty for a
// name that is not a command of the table.
std::string command_help(std::string_view command);

// `hapscene completion bash`: a bash script that completes commands, options per command,
// environment files, folders and enumerated values.
std::string bash_completion_script();

// `hapscene man`: the man page, section 1, in roff (man -l, groff -man); `version` on its
// title line.
std::string man_page(std::string_view version);

// `hapscene man --markdown`: the same reference as Markdown (docs/reference/options.md).
std::string command_reference_markdown(std::string_view version);

// Shared by the generators: "-D, --device SPEC", and "default 2 s; range (0, 86400] s".
std::string option_label(const OptionDefinition& option);
std::string option_details(const OptionDefinition& option);

// The paragraphs every description ends with (values with units; exit codes).
inline constexpr std::string_view kValuesNote =
    "Values take SI numbers or strings with units (\"10 mm\", \"2 kHz\", \"3s\"; \"--duration 3 s\" reads as "
    "3 s); each numeric option has a range, and a value outside it is invalid input.";
inline constexpr std::string_view kExitNote =
    "Exit codes: 0 success; 2 invalid input (a file, a value, an argument; the message names the place); 1 "
    "anything else: a check or expectation that failed, a fault seen in a run, output that could not be "
    "written.";

}  // namespace hapscene
