#pragma once
// `hapscene devices`: the serial ports that look like boards and which of them answer
// hapscene's handshake.
//
// Listing reads the file system only: /dev/serial/by-id (udev's stable names), /dev/ttyACM*
// and /dev/ttyUSB*, and for each tty its USB identity from sysfs
// (/sys/class/tty/NAME/device/../idVendor, idProduct, manufacturer, product, serial).
// Everything is read under `root` ("/" normally; tests pass a directory laid out the same
// way, through HAPSCENE_DEVICES_ROOT).
//
// Probing opens every listed port at once and runs the board protocol's handshake on them
// (BoardLink: HELLO every 100 ms, nothing else until a board answers; the HELLO_REPLY
// carries the firmware version), then closes them. A port that never answers only ever
// receives HELLO frames.
#include <optional>
#include <string>
#include <vector>

namespace hapscene {

struct SerialPortEntry {
  std::string path;                 // /dev/ttyACM0 (under root)
  std::vector<std::string> by_id;   // /dev/serial/by-id/... names pointing at it
  // USB identity from sysfs (empty when not a USB device or not readable).
  std::string usb_vendor, usb_product;  // hex ids, "2341", "0043"
  std::string manufacturer, product, serial;
};

// What a port said to the handshake.
struct PortProbe {
  bool opened{};
  std::string open_error;  // why it could not be opened (with the fix for a permission)
  bool answered{};         // a hapscene board: HELLO_REPLY of this protocol version
  std::string firmware;    // "0.1.0"
  unsigned protocol{};
  unsigned board_kind{};
  std::string board;       // "Hapkit 3.0"
  std::string failure;     // no answer: what arrived (handshake_failure's words)
};

// The ports under `root`, sorted by path; by-id links to other devices are listed as
// their own entries only when they point at a character device.
std::vector<SerialPortEntry> list_serial_ports(const std::string& root);

// The root to list: HAPSCENE_DEVICES_ROOT when set (for tests), else "/".
std::string devices_root();

// Runs the handshake on every port at once for at most `timeout_s` (wall time).
std::vector<PortProbe> probe_ports(const std::vector<SerialPortEntry>& ports, int baud, double timeout_s);

// A known maker of USB serial chips and boards by USB vendor id ("2341": "Arduino"), or "".
std::string usb_vendor_name(const std::string& vendor_id);

}  // namespace hapscene
