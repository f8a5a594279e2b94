#include "engine/devices/hil/firmware_image.hpp"

#include "engine/base/json_source.hpp"

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string_view>
#include <vector>

#include "engine/base/errors.hpp"
#include "engine/base/json_source.hpp"

namespace hapscene {
namespace {

// ELF32 constants (the few this check needs).
constexpr std::size_t kEhdrSize = 52, kPhdrSize = 32, kShdrSize = 40, kSymSize = 16;
constexpr std::uint16_t kEtExec = 2, kEmAvr = 83;
constexpr std::uint32_t kPtLoad = 1;
constexpr std::uint32_t kShtNull = 0, kShtSymtab = 2, kShtStrtab = 3, kShtNobits = 8;
constexpr std::uint32_t kShfKnown = 0x7ff;  // SHF_WRITE .. SHF_TLS
constexpr std::uint32_t kShfAlloc = 0x2;

// The file, read little-endian with every access inside it.
class Image {
 public:
  Image(std::vector<std::uint8_t> bytes, const std::string& path) : bytes_(std::move(bytes)), path_(path) {}
  std::uint64_t size() const { return bytes_.size(); }
  std::uint16_t u16(std::uint64_t at) const {
    need(at, 2, "a header");
    return static_cast<std::uint16_t>(bytes_[at] | (bytes_[at + 1] << 8));
  }
  std::uint32_t u32(std::uint64_t at) const {
    need(at, 4, "a header");
    return static_cast<std::uint32_t>(bytes_[at]) | (static_cast<std::uint32_t>(bytes_[at + 1]) << 8) |
           (static_cast<std::uint32_t>(bytes_[at + 2]) << 16) | (static_cast<std::uint32_t>(bytes_[at + 3]) << 24);
  }
  std::uint8_t u8(std::uint64_t at) const {
    need(at, 1, "a header");
    return bytes_[at];
  }
  // [at, at + length) inside the file (64-bit sums of 32-bit fields cannot overflow).
  void need(std::uint64_t at, std::uint64_t length, const std::string& what) const {
    if (at + length > bytes_.size()) {
      fail(what + " lies outside the file (bytes " + std::to_string(at) + ".." + std::to_string(at + length) +
           " of " + std::to_string(bytes_.size()) + "): truncated or corrupt");
    }
  }
  // A NUL-terminated string at table_offset + index within a table of table_size bytes.
  std::string_view string(std::uint64_t table_offset, std::uint64_t table_size, std::uint64_t index,
                          const std::string& what) const {
    if (index >= table_size) fail(what + ": name index " + std::to_string(index) + " beyond its string table");
    const auto* begin = reinterpret_cast<const char*>(bytes_.data() + table_offset + index);
    const std::size_t room = table_size - index;
    const std::size_t length = strnlen(begin, room);
    if (length == room) fail(what + ": name not terminated within its string table");
    return {begin, length};
  }
  [[noreturn]] void fail(const std::string& message) const {
    throw InputError("--device hil:" + path_ + ": not a valid ATmega328P firmware: " + message);
  }

 private:
  std::vector<std::uint8_t> bytes_;
  std::string path_;
};

std::string hex(std::uint64_t value) {
  char text[24];
  std::snprintf(text, sizeof text, "0x%llX", static_cast<unsigned long long>(value));
  return text;
}

// [begin, begin + size) inside [low, high).
bool within(std::uint64_t begin, std::uint64_t size, std::uint64_t low, std::uint64_t high) {
  return begin >= low && begin + size <= high;
}

}  // namespace

void check_avr_firmware(const std::string& path) {
  // Read it whole, through the reader every file goes through: bounded, and a named
  // pipe, directory or device is refused instead of blocking.
  std::string text;
  try {
    text = read_text_file(path, kMaxFirmwareFileBytes);
  } catch (const InputError& error) {
    throw InputError(std::string("--device hil:") + error.what());
  }
  std::vector<std::uint8_t> bytes(text.begin(), text.end());
  const Image image(std::move(bytes), path);

  // The ELF header: 32-bit, little-endian, an AVR executable.
  if (image.size() < kEhdrSize) image.fail("too short for an ELF header (" + std::to_string(image.size()) + " bytes)");
  if (!(image.u8(0) == 0x7F && image.u8(1) == 'E' && image.u8(2) == 'L' && image.u8(3) == 'F')) {
    image.fail("no ELF signature (an .elf is needed; a .hex is for flashing a real board)");
  }
  if (image.u8(4) != 1 || image.u8(5) != 1 || image.u8(6) != 1) {
    image.fail("not a 32-bit little-endian ELF of version 1");
  }
  const std::uint16_t type = image.u16(16), machine = image.u16(18);
  if (machine != kEmAvr) image.fail("built for machine " + std::to_string(machine) + ", not AVR (83)");
  if (type != kEtExec) image.fail("ELF type " + std::to_string(type) + ", not an executable (2)");
  if (image.u32(20) != 1) image.fail("ELF version " + std::to_string(image.u32(20)) + ", not 1");
  const std::uint32_t entry = image.u32(24), phoff = image.u32(28), shoff = image.u32(32);
  const std::uint16_t ehsize = image.u16(40), phentsize = image.u16(42), phnum = image.u16(44);
  const std::uint16_t shentsize = image.u16(46), shnum = image.u16(48), shstrndx = image.u16(50);
  if (ehsize != kEhdrSize) image.fail("ELF header size " + std::to_string(ehsize) + ", not 52");
  if (entry >= kAvrFlashBytes || entry % 2 != 0) image.fail("entry point " + hex(entry) + " is not a word in flash");

  // Program headers: load segments inside the file and the MCU's memories, no overlaps.
  if (phnum == 0) image.fail("no program headers");
  if (phentsize != kPhdrSize) image.fail("program header size " + std::to_string(phentsize) + ", not 32");
  image.need(phoff, std::uint64_t{phnum} * kPhdrSize, "the program header table");
  struct AddressSpan { std::uint64_t begin, end; };
  std::vector<AddressSpan> flash_ranges, ram_ranges;
  for (std::uint16_t i = 0; i < phnum; ++i) {
    const std::uint64_t at = phoff + std::uint64_t{i} * kPhdrSize;
    if (image.u32(at) != kPtLoad) continue;
    const std::string what = "load segment " + std::to_string(i);
    const std::uint32_t offset = image.u32(at + 4), vaddr = image.u32(at + 8), paddr = image.u32(at + 12);
    const std::uint32_t filesz = image.u32(at + 16), memsz = image.u32(at + 20);
    image.need(offset, filesz, what);
    if (filesz > memsz) image.fail(what + ": more bytes in the file (" + std::to_string(filesz) + ") than in memory (" + std::to_string(memsz) + ")");
    // Its bytes go to flash when they have any (its load address); memory-only ones to RAM.
    if (filesz > 0) {
      if (!within(paddr, filesz, 0, kAvrFlashBytes) && !within(paddr, filesz, kAvrEepromStart, kAvrEepromStart + kAvrEepromBytes)) {
        image.fail(what + ": " + std::to_string(filesz) + " bytes at " + hex(paddr) + " do not fit the 32 KB of flash");
      }
      if (paddr < kAvrFlashBytes) flash_ranges.push_back({paddr, std::uint64_t{paddr} + filesz});
    }
    if (vaddr >= 0x800000 && vaddr < kAvrEepromStart) {
      if (!within(vaddr, memsz, kAvrRamStart, kAvrRamEnd)) {
        image.fail(what + ": " + std::to_string(memsz) + " bytes at " + hex(vaddr) + " do not fit the 2 KB of RAM");
      }
      ram_ranges.push_back({vaddr, std::uint64_t{vaddr} + memsz});
    }
  }
  for (const auto* ranges : {&flash_ranges, &ram_ranges}) {
    for (std::size_t a = 0; a < ranges->size(); ++a) {
      for (std::size_t b = a + 1; b < ranges->size(); ++b) {
        const AddressSpan& x = (*ranges)[a];
        const AddressSpan& y = (*ranges)[b];
        if (x.begin < y.end && y.begin < x.end) {
          image.fail("load segments overlap at " + hex(std::max(x.begin, y.begin)));
        }
      }
    }
  }

  // Section headers: simavr finds .text, .data, .bss, .eeprom and the symbols by section.
  if (shnum == 0) image.fail("no section headers");
  if (shentsize != kShdrSize) image.fail("section header size " + std::to_string(shentsize) + ", not 40");
  image.need(shoff, std::uint64_t{shnum} * kShdrSize, "the section header table");
  if (shstrndx >= shnum) image.fail("the section name table index " + std::to_string(shstrndx) + " is not a section");
  const auto section_at = [&](std::uint32_t index) { return shoff + std::uint64_t{index} * kShdrSize; };
  const std::uint64_t names_at = section_at(shstrndx);
  if (image.u32(names_at + 4) != kShtStrtab) image.fail("the section name table is not a string table");
  const std::uint32_t names_offset = image.u32(names_at + 16), names_size = image.u32(names_at + 20);
  image.need(names_offset, names_size, "the section name table");
  std::uint64_t text_size = 0, data_size = 0;
  bool has_text = false;
  for (std::uint16_t i = 0; i < shnum; ++i) {
    const std::uint64_t at = section_at(i);
    const std::uint32_t sh_type = image.u32(at + 4);
    if (sh_type == kShtNull) continue;
    const std::string_view name = image.string(names_offset, names_size, image.u32(at), "section " + std::to_string(i));
    const std::string what = "section " + std::string(name);
    const std::uint32_t flags = image.u32(at + 8), addr = image.u32(at + 12);
    const std::uint32_t offset = image.u32(at + 16), size = image.u32(at + 20);
    const std::uint32_t link = image.u32(at + 24), entsize = image.u32(at + 36);
    if (sh_type != kShtNobits) image.need(offset, size, what);
    // Only the plain flags (write, alloc, exec, merge, strings, info-link, link-order,
    // OS, group, TLS): a compressed section (0x800) or unknown bits make libelf hand
    // simavr data that is not what the header says, and simavr then reads out of bounds.
    if ((flags & ~kShfKnown) != 0) image.fail(what + ": section flags " + hex(flags) + " (compressed or unknown)");
    if (name == ".mmcu") image.fail("a .mmcu section (simavr metadata the hapscene firmware does not carry)");
    if (name == ".text") {
      has_text = true;
      text_size = size;
      if (!within(addr, size, 0, kAvrFlashBytes)) image.fail(what + " (" + std::to_string(size) + " bytes at " + hex(addr) + ") does not fit the 32 KB of flash");
    } else if (name == ".data") {
      data_size = size;
    } else if (name == ".eeprom") {
      if (!within(addr, size, kAvrEepromStart, kAvrEepromStart + kAvrEepromBytes)) image.fail(what + " does not fit the 1 KB of EEPROM");
    }
    if ((flags & kShfAlloc) != 0 && addr >= 0x800000 && addr < kAvrEepromStart &&
        !within(addr, size, kAvrRamStart, kAvrRamEnd)) {
      image.fail(what + " (" + std::to_string(size) + " bytes at " + hex(addr) + ") does not fit the 2 KB of RAM");
    }
    if (sh_type == kShtSymtab) {
      // Symbols, and the names simavr reads through them.
      if (entsize != kSymSize || size % kSymSize != 0) image.fail(what + ": symbol entries of " + std::to_string(entsize) + " bytes, not 16");
      if (link >= shnum) image.fail(what + ": its string table " + std::to_string(link) + " is not a section");
      const std::uint64_t strings_at = section_at(link);
      if (image.u32(strings_at + 4) != kShtStrtab) image.fail(what + ": linked to a section that is not a string table");
      const std::uint32_t strings_offset = image.u32(strings_at + 16), strings_size = image.u32(strings_at + 20);
      image.need(strings_offset, strings_size, what + "'s string table");
      for (std::uint64_t s = 0; s < size / kSymSize; ++s) {
        const std::uint64_t symbol_at = offset + s * kSymSize;
        image.string(strings_offset, strings_size, image.u32(symbol_at), what + " entry " + std::to_string(s));
      }
    }
  }
  if (!has_text) image.fail("no .text section (no code)");
  if (text_size + data_size > kAvrFlashBytes) {
    image.fail(".text and .data need " + std::to_string(text_size + data_size) + " bytes of flash, more than 32 KB");
  }
}

}  // namespace hapscene
