#pragma once
// Checks a firmware file before simavr sees it. simavr trusts its input: a truncated or
// mutated .elf can make it read past its buffers or abort. Everything simavr reads is
// checked here against the file and the ATmega328P: an ELF32 little-endian AVR
// executable; every header table, section and segment inside the file; the code (.text
// and .data's initial values) inside the 32 KB of flash; .data, .bss and .noinit inside
// the 2 KB of RAM; load segments not overlapping; the entry point in flash; symbol and
// string tables well formed (simavr reads the symbol names).
#include <string>

namespace hapscene {

// The ATmega328P's memories, as the AVR toolchain addresses them in an .elf.
inline constexpr unsigned kAvrFlashBytes = 32 * 1024;
inline constexpr unsigned kAvrRamStart = 0x800100;   // after registers and I/O
inline constexpr unsigned kAvrRamEnd = 0x800900;     // 2 KB of SRAM
inline constexpr unsigned kAvrEepromStart = 0x810000;
inline constexpr unsigned kAvrEepromBytes = 1024;
// Larger files are refused without reading them (the firmware is about 12 kB).
inline constexpr unsigned long kMaxFirmwareFileBytes = 16ul * 1024 * 1024;

// Throws InputError naming `path` and the first problem found; returns when the file is
// a plausible ATmega328P firmware image.
void check_avr_firmware(const std::string& path);

}  // namespace hapscene
