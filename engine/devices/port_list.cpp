#include "engine/devices/port_list.hpp"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <system_error>
#include <thread>

#include "engine/base/clock.hpp"
#include "engine/base/errors.hpp"
#include "engine/base/format.hpp"
#include "engine/devices/board_link.hpp"
#include "engine/devices/board_report.hpp"
#include "engine/devices/serial_port.hpp"

namespace hapscene {
namespace fs = std::filesystem;
namespace {

// The first line of a small sysfs attribute, printable; "" when absent.
std::string read_attribute(const fs::path& path) {
  std::ifstream in(path);
  if (!in) return {};
  char buffer[256]{};
  in.getline(buffer, sizeof buffer);
  std::string text(buffer);
  while (!text.empty() && (text.back() == ' ' || text.back() == '\r')) text.pop_back();
  return printable(text);
}

// The USB device a tty belongs to: the nearest parent of /sys/class/tty/NAME/device that
// has an idVendor (the interface's parent for ttyACM, one more level for ttyUSB).
void read_usb_identity(const fs::path& sys_root, const std::string& tty, SerialPortEntry* entry) {
  std::error_code error;
  fs::path dir = fs::canonical(sys_root / "class" / "tty" / tty / "device", error);
  if (error) return;
  for (int level = 0; level < 5 && !dir.empty() && dir != dir.root_path(); ++level, dir = dir.parent_path()) {
    if (!fs::exists(dir / "idVendor", error)) continue;
    entry->usb_vendor = read_attribute(dir / "idVendor");
    entry->usb_product = read_attribute(dir / "idProduct");
    entry->manufacturer = read_attribute(dir / "manufacturer");
    entry->product = read_attribute(dir / "product");
    entry->serial = read_attribute(dir / "serial");
    return;
  }
}

bool is_board_tty(const std::string& name) {
  return name.starts_with("ttyACM") || name.starts_with("ttyUSB");
}

// ttyACM2 before ttyACM10.
bool natural_less(const std::string& a, const std::string& b) {
  const auto split = [](const std::string& s) {
    std::size_t digits = s.size();
    while (digits > 0 && s[digits - 1] >= '0' && s[digits - 1] <= '9') --digits;
    const long number = digits < s.size() ? std::strtol(s.c_str() + digits, nullptr, 10) : -1;
    return std::pair<std::string, long>(s.substr(0, digits), number);
  };
  return split(a) < split(b);
}

}  // namespace

std::string devices_root() {
  const char* root = std::getenv("HAPSCENE_DEVICES_ROOT");
  return root != nullptr && *root != '\0' ? std::string(root) : std::string("/");
}

std::string usb_vendor_name(const std::string& vendor_id) {
  struct Maker {
    const char* id;
    const char* name;
  };
  // Makers of Arduino-style boards and of the USB serial chips they carry.
  static constexpr Maker kMakers[] = {
      {"2341", "Arduino"}, {"2a03", "Arduino"}, {"1a86", "QinHeng (CH340)"}, {"0403", "FTDI"},
      {"10c4", "Silicon Labs (CP210x)"}, {"239a", "Adafruit"}, {"1b4f", "SparkFun"}, {"16c0", "Van Ooijen (Teensy)"},
      {"067b", "Prolific"}, {"2e8a", "Raspberry Pi"}};
  for (const Maker& maker : kMakers) {
    if (vendor_id == maker.id) return maker.name;
  }
  return {};
}

std::vector<SerialPortEntry> list_serial_ports(const std::string& root) {
  const fs::path base(root.empty() ? "/" : root);
  const fs::path dev = base / "dev";
  std::vector<SerialPortEntry> ports;
  std::error_code error;

  // /dev/ttyACM*, /dev/ttyUSB*
  std::vector<std::string> names;
  for (fs::directory_iterator it(dev, error), end; !error && it != end; it.increment(error)) {
    const std::string name = it->path().filename().string();
    if (is_board_tty(name)) names.push_back(name);
  }
  std::sort(names.begin(), names.end(), natural_less);
  for (const std::string& name : names) {
    SerialPortEntry entry;
    entry.path = (dev / name).lexically_normal().string();
    read_usb_identity(base / "sys", name, &entry);
    ports.push_back(entry);
  }

  // udev's stable names: each points at one of the ttys (relative links, "../../ttyACM0").
  std::vector<fs::path> links;
  for (fs::directory_iterator it(dev / "serial" / "by-id", error), end; !error && it != end; it.increment(error)) {
    links.push_back(it->path());
  }
  std::sort(links.begin(), links.end());
  for (const fs::path& link : links) {
    std::error_code link_error;
    const fs::path target = fs::read_symlink(link, link_error);
    if (link_error) continue;
    const fs::path resolved =
        (target.is_absolute() ? base / target.relative_path() : link.parent_path() / target).lexically_normal();
    auto found = std::find_if(ports.begin(), ports.end(),
                              [&](const SerialPortEntry& port) { return port.path == resolved.string(); });
    if (found == ports.end()) {
      // A board on another kind of tty: listed under its own name.
      SerialPortEntry entry;
      entry.path = resolved.string();
      read_usb_identity(base / "sys", resolved.filename().string(), &entry);
      ports.push_back(entry);
      found = ports.end() - 1;
    }
    found->by_id.push_back(link.lexically_normal().string());
  }
  return ports;
}

std::vector<PortProbe> probe_ports(const std::vector<SerialPortEntry>& ports, int baud, double timeout_s) {
  std::vector<PortProbe> probes(ports.size());
  std::vector<std::unique_ptr<SerialPort>> opened(ports.size());
  std::vector<std::unique_ptr<BoardLink>> links(ports.size());
  BoardLinkConfig config;  // HELLO every 100 ms until an answer
  for (std::size_t i = 0; i < ports.size(); ++i) {
    try {
      opened[i] = std::make_unique<SerialPort>(ports[i].path, baud, ports[i].path);
      links[i] = std::make_unique<BoardLink>(*opened[i], config);
      probes[i].opened = true;
    } catch (const InputError& failure) {
      // "PATH: cannot open PATH: why": keep from "cannot open".
      const std::string message = failure.what();
      const std::size_t from = message.find("cannot open");
      probes[i].open_error = from == std::string::npos ? message : message.substr(from);
    }
  }

  // All ports at once, as the two-board handshake does: Uno-style boards reset when their
  // port opens and answer after their bootloader's wait.
  const std::int64_t deadline_ns = monotonic_now_ns() + static_cast<std::int64_t>(timeout_s * 1e9);
  for (;;) {
    bool waiting = false;
    const std::int64_t now_ns = monotonic_now_ns();
    for (const auto& link : links) {
      if (!link || link->state() == LinkState::running || link->handshake_seen().other_version) continue;
      waiting = true;
      link->send(MotorCommand{}, now_ns);  // a HELLO while handshaking, nothing else
      link->poll(now_ns);
    }
    if (!waiting || now_ns > deadline_ns) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }

  for (std::size_t i = 0; i < ports.size(); ++i) {
    if (!links[i]) continue;
    const BoardLink& link = *links[i];
    PortProbe& probe = probes[i];
    if (link.identified()) {
      const hs_hello_reply& id = link.identity();
      probe.firmware = printf_string("%u.%u.%u", id.firmware_major, id.firmware_minor, id.firmware_patch);
      probe.protocol = id.protocol_version;
      probe.board_kind = id.board_kind;
      probe.board = id.board_kind == HS_BOARD_HAPKIT3 ? "Hapkit 3.0" : printf_string("board kind %u", id.board_kind);
    }
    probe.answered = link.state() == LinkState::running;
    if (!probe.answered) probe.failure = handshake_failure(link);
  }
  return probes;
}

}  // namespace hapscene
