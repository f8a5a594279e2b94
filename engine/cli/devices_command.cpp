// `hapscene devices [--json] [--no-probe] [--timeout T] [--baud N]`: the serial ports that
// look like boards (engine/devices/port_list.hpp), with their USB identity, and which of
// them answer hapscene's handshake with which firmware.
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "engine/base/errors.hpp"
#include "engine/base/format.hpp"
#include "engine/base/object_reader.hpp"
#include "engine/base/units.hpp"
#include "engine/cli/arguments.hpp"
#include "engine/cli/commands.hpp"
#include "engine/cli/option_definitions.hpp"
#include "engine/cli/standard_output.hpp"
#include "engine/devices/port_list.hpp"

namespace hapscene {
namespace {

// "2341:0043 Arduino Uno (Arduino LLC)" or "not USB".
std::string usb_text(const SerialPortEntry& port) {
  if (port.usb_vendor.empty()) return "(no USB identity)";
  std::string text = port.usb_vendor + ":" + port.usb_product;
  const std::string maker = !port.manufacturer.empty() ? port.manufacturer : usb_vendor_name(port.usb_vendor);
  if (!port.product.empty()) text += " " + port.product;
  if (!maker.empty()) text += " (" + maker + ")";
  return text;
}

std::string probe_text(const PortProbe& probe, bool probed, double timeout_s) {
  if (!probed) return "not probed";
  if (!probe.opened) return probe.open_error;
  if (probe.answered) {
    return "hapscene firmware " + probe.firmware + ", protocol " + std::to_string(probe.protocol) + ", " + probe.board;
  }
  return "no hapscene answer within " + format_number(timeout_s) + " s: " + probe.failure;
}

nlohmann::json port_json(const SerialPortEntry& port, const PortProbe& probe, bool probed) {
  nlohmann::json entry{{"port", port.path},       {"by_id", port.by_id},         {"usb_vendor", port.usb_vendor},
                       {"usb_product", port.usb_product}, {"manufacturer", port.manufacturer},
                       {"product", port.product}, {"serial", port.serial}};
  if (!probed) return entry;
  entry["opened"] = probe.opened;
  entry["answered"] = probe.answered;
  if (!probe.opened) entry["error"] = probe.open_error;
  if (!probe.firmware.empty()) {
    entry["firmware"] = probe.firmware;
    entry["protocol"] = probe.protocol;
    entry["board_kind"] = probe.board_kind;
  }
  if (probe.opened && !probe.answered) entry["error"] = probe.failure;
  return entry;
}

}  // namespace

int devices_command(std::vector<std::string> args) {
  Arguments arguments(std::move(args), "hapscene devices");
  const bool json = arguments.take_flag("json");
  const bool probe = !arguments.take_flag("no-probe");
  const double timeout_s = arguments.take(option::devices_timeout).value_or(2.5);
  const int baud = static_cast<int>(arguments.take(option::baud).value_or(1000000));
  if (!arguments.positionals().empty()) arguments.fail("takes no files (options: --json, --no-probe, --timeout T, --baud N)");

  const std::vector<SerialPortEntry> ports = list_serial_ports(devices_root());
  const std::vector<PortProbe> probes = probe ? probe_ports(ports, baud, timeout_s) : std::vector<PortProbe>(ports.size());

  if (json) {
    nlohmann::json list = nlohmann::json::array();
    for (std::size_t i = 0; i < ports.size(); ++i) list.push_back(port_json(ports[i], probes[i], probe));
    write_out(list.dump(2) + "\n");
    return kExitOk;
  }
  if (ports.empty()) {
    print_out("no serial ports found (/dev/ttyACM*, /dev/ttyUSB*, /dev/serial/by-id): is the board plugged in "
              "with a data cable?\n");
    return kExitOk;
  }
  // One block per port: where it is, what USB says it is, what it answered.
  const SerialPortEntry* first_board = nullptr;
  for (std::size_t i = 0; i < ports.size(); ++i) {
    const SerialPortEntry& port = ports[i];
    print_out("%s\n", printable(port.path).c_str());
    for (const std::string& id : port.by_id) print_out("  by-id     %s\n", printable(id).c_str());
    print_out("  usb       %s%s\n", usb_text(port).c_str(),
              port.serial.empty() ? "" : (", serial " + port.serial).c_str());
    print_out("  answers   %s\n", printable(probe_text(probes[i], probe, timeout_s)).c_str());
    if (probes[i].answered && first_board == nullptr) first_board = &port;
  }
  if (first_board != nullptr) {
    // The by-id name stays the same whichever port number the board gets.
    const std::string path = first_board->by_id.empty() ? first_board->path : first_board->by_id.front();
    print_out("\nrun on it:  hapscene run ENV --device serial:%s\n", printable(path).c_str());
  }
  return kExitOk;
}

}  // namespace hapscene
