// `hapscene man`: the man page (section 1, roff with the man macros), written from the
// table of engine/cli/command_definitions.cpp.
#include <string>

#include "engine/cli/help_text.hpp"

namespace hapscene {
namespace {

// Text as roff reads it: backslashes escaped, hyphens as minus signs (options, values),
// and no line that starts with a control character.
std::string roff(std::string_view text) {
  std::string out;
  for (const char c : text) {
    if (c == '\\') out += "\\e";
    else if (c == '-') out += "\\-";
    else out += c;
  }
  if (!out.empty() && (out[0] == '.' || out[0] == '\'')) out.insert(0, "\\&");
  return out;
}

}  // namespace

std::string man_page(std::string_view version) {
  std::string out;
  out += ".TH HAPSCENE 1 \"\" \"hapscene " + roff(version) + "\" \"User Commands\"\n";
  out += ".SH NAME\nhapscene \\- a data\\-driven haptic rendering engine\n";
  out += ".SH SYNOPSIS\n";
  for (const CommandDefinition& form : command_definitions()) {
    out += ".B hapscene " + roff(form.name) + "\n";
    std::string rest;
    if (!form.mode.empty()) rest += "\\-\\-" + roff(form.mode) + " ";
    rest += roff(form.synopsis);
    out += rest + "\n.br\n";
  }
  for (const BuiltinCommand& builtin : builtin_commands()) {
    out += ".B hapscene " + roff(builtin.name) + "\n" + (builtin.synopsis.empty() ? "" : roff(builtin.synopsis) + "\n") +
           ".br\n";
  }
  out += ".B hapscene \\-\\-version\n";
  out += ".SH DESCRIPTION\n";
  out += "hapscene renders haptic environments (JSON or Lua files) on a 1\\-DOF Stanford Hapkit, a 2\\-DOF "
         "device, a simulated one, or the firmware on a simulated board, and checks them with a test harness.\n";
  out += ".PP\n" + roff(kValuesNote) + "\n";
  out += ".SH COMMANDS\n";
  for (const CommandDefinition& form : command_definitions()) {
    std::string title = "hapscene " + std::string(form.name);
    if (!form.mode.empty()) title += " --" + std::string(form.mode);
    if (!form.synopsis.empty()) title += " " + std::string(form.synopsis);
    out += ".SS \"" + roff(title) + "\"\n";
    out += roff(form.summary) + ".\n" + roff(form.description) + "\n";
    for (const OptionDefinition& option : form.options) {
      out += ".TP\n";
      std::string label;
      if (option.short_name != 0) label += "\\fB\\-" + std::string(1, option.short_name) + "\\fR, ";
      label += "\\fB\\-\\-" + roff(option.name) + "\\fR";
      if (!option.value_name.empty()) label += " \\fI" + roff(option.value_name) + "\\fR";
      out += label + "\n" + roff(option.help);
      const std::string details = option_details(option);
      out += details.empty() ? std::string(".\n") : " (" + roff(details) + ").\n";
    }
    if (!form.examples.empty()) {
      out += ".PP\nExamples:\n.PP\n.RS\n.nf\n";
      for (const std::string_view example : form.examples) out += "hapscene " + roff(example) + "\n";
      out += ".fi\n.RE\n";
    }
  }
  out += ".SS \"Other commands\"\n";
  for (const BuiltinCommand& builtin : builtin_commands()) {
    out += ".TP\n\\fBhapscene " + roff(builtin.name) + "\\fR";
    if (!builtin.synopsis.empty()) out += " " + roff(builtin.synopsis);
    out += "\n" + roff(builtin.summary) + ".\n";
  }
  out += ".TP\n\\fBhapscene \\-\\-version\\fR, \\fB\\-V\\fR\nThe version.\n";
  out += ".TP\n\\fBhapscene\\fR \\fICOMMAND\\fR \\fB\\-\\-help\\fR, \\fB\\-h\\fR\nThe command's usage, options and "
         "examples (also \\fBhapscene help\\fR \\fICOMMAND\\fR).\n";
  out += ".SH \"EXIT STATUS\"\n" + roff(kExitNote) + "\n";
  out += ".SH FILES\n.TP\n.I environments/\nThe shipped environments (*.json, *.lua) and their test specs "
         "(*.test.json).\n.TP\n.I scripts/\nLua scripts and their specs.\n";
  out += ".SH \"SEE ALSO\"\nThe documentation in /usr/share/doc/hapscene (README.md, docs/, and html/ when built) or in "
         "the sources: tutorials, environment files, scripts, device profiles, the test harness and the device path.\n";
  return out;
}

}  // namespace hapscene
