#include "engine/devices/hil/board/simavr_board.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstdarg>
#include <cstring>
#include <stdexcept>


extern "C" {
#include <avr_adc.h>
#include <avr_ioport.h>
#include <avr_uart.h>
#include <sim_avr.h>
#include <sim_elf.h>
}

namespace hapscene {
namespace {

// Register addresses in the data space of the ATmega328P (I/O address + 0x20).
constexpr std::uint16_t kPortB = 0x25;
constexpr std::uint16_t kDdrD = 0x2A;
constexpr std::uint16_t kPortD = 0x2B;
constexpr std::uint16_t kTccr0A = 0x44;
constexpr std::uint16_t kOcr0B = 0x48;
constexpr std::uint8_t kCom0B1 = 1u << 5;
constexpr std::uint8_t kPin5 = 1u << 5;

constexpr std::uint32_t kVref_mV = 5000;

// simavr's own messages: errors only, and at most kMaxLogBytes in all (nobody may read
// them before the run ends, and a full pipe would stall the board).
constexpr std::size_t kMaxLogBytes = 4000;
std::size_t logged_bytes = 0;
void quiet_logger(avr_t* /*avr*/, const int level, const char* format, va_list args) {
  if (level > LOG_ERROR || logged_bytes >= kMaxLogBytes) return;
  char line[512];
  const int n = std::vsnprintf(line, sizeof line, format, args);
  if (n <= 0) return;
  const std::size_t size = std::min<std::size_t>({static_cast<std::size_t>(n), sizeof line - 1, kMaxLogBytes - logged_bytes});
  logged_bytes += size;
  std::fwrite(line, 1, size, stderr);
  std::fflush(stderr);
}

// The simulated board never waits in real time.
void no_sleep(avr_t* /*avr*/, avr_cycle_count_t /*how_long*/) {}

}  // namespace

bool simavr_trial_boot(const std::string& firmware_elf) {
  constexpr std::uint64_t kTrialCycles = 16'000'000 / 100;  // 10 ms of the board's life
  avr_global_logger_set(quiet_logger);
  static elf_firmware_t firmware;
  std::memset(&firmware, 0, sizeof firmware);
  if (elf_read_firmware(firmware_elf.c_str(), &firmware) != 0) return false;
  avr_t* avr = avr_make_mcu_by_name("atmega328p");
  if (avr == nullptr) return false;
  avr_init(avr);
  avr->frequency = SimavrBoard::kClock_Hz;
  avr->log = LOG_ERROR;
  avr->sleep = no_sleep;
  avr_load_firmware(avr, &firmware);
  while (avr->cycle < kTrialCycles) {
    const int state = avr_run(avr);
    if (state == cpu_Done || state == cpu_Crashed) break;
  }
  avr_terminate(avr);
  std::free(avr);
  return true;
}

struct SimavrBoard::Impl {
  avr_t* avr{};
  std::unique_ptr<elf_firmware_t> firmware;
  avr_irq_t* uart_input{};
  avr_irq_t* adc2{};
  bool uart_blocked{};
  // Host -> board bytes waiting for FIFO room; board -> host bytes waiting to be taken.
  std::array<std::uint8_t, 4096> to_board{};
  std::size_t to_board_head{}, to_board_count{};
  std::array<std::uint8_t, 4096> to_host{};
  std::size_t to_host_head{}, to_host_count{};

  // Pushes queued bytes into the UART until its FIFO says it is full.
  void pump() noexcept {
    while (!uart_blocked && to_board_count > 0) {
      const std::uint8_t byte = to_board[to_board_head];
      to_board_head = (to_board_head + 1) % to_board.size();
      --to_board_count;
      avr_raise_irq(uart_input, byte);
    }
  }

  static void on_output(avr_irq_t* /*irq*/, std::uint32_t value, void* param) {
    auto* self = static_cast<Impl*>(param);
    if (self->to_host_count == self->to_host.size()) return;  // nobody reads: drop
    self->to_host[(self->to_host_head + self->to_host_count) % self->to_host.size()] =
        static_cast<std::uint8_t>(value);
    ++self->to_host_count;
  }
  static void on_xon(avr_irq_t* /*irq*/, std::uint32_t /*value*/, void* param) {
    auto* self = static_cast<Impl*>(param);
    self->uart_blocked = false;
    self->pump();
  }
  static void on_xoff(avr_irq_t* /*irq*/, std::uint32_t /*value*/, void* param) {
    static_cast<Impl*>(param)->uart_blocked = true;
  }
};

SimavrBoard::SimavrBoard(const std::string& firmware_elf) : impl_(std::make_unique<Impl>()) {
  avr_global_logger_set(quiet_logger);
  impl_->firmware = std::make_unique<elf_firmware_t>();
  std::memset(impl_->firmware.get(), 0, sizeof(elf_firmware_t));
  if (elf_read_firmware(firmware_elf.c_str(), impl_->firmware.get()) != 0) {
    throw std::runtime_error("not a readable AVR firmware image");
  }

  // An ATmega328P at 16 MHz with a 5 V supply and reference.
  avr_t* avr = avr_make_mcu_by_name("atmega328p");
  if (avr == nullptr) throw std::runtime_error("simavr has no atmega328p core");
  impl_->avr = avr;
  avr_init(avr);
  avr->frequency = kClock_Hz;
  avr->vcc = avr->avcc = avr->aref = kVref_mV;
  avr->log = LOG_ERROR;
  avr->sleep = no_sleep;
  avr_load_firmware(avr, impl_->firmware.get());
  avr->frequency = kClock_Hz;  // the image may carry another one

  // UART0: no console echo, no real-time sleeping while the firmware polls.
  std::uint32_t flags = 0;
  avr_ioctl(avr, AVR_IOCTL_UART_GET_FLAGS('0'), &flags);
  flags &= ~static_cast<std::uint32_t>(AVR_UART_FLAG_POLL_SLEEP | AVR_UART_FLAG_STDIO);
  avr_ioctl(avr, AVR_IOCTL_UART_SET_FLAGS('0'), &flags);
  impl_->uart_input = avr_io_getirq(avr, AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_INPUT);
  avr_irq_register_notify(avr_io_getirq(avr, AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_OUTPUT),
                          Impl::on_output, impl_.get());
  avr_irq_register_notify(avr_io_getirq(avr, AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_OUT_XON),
                          Impl::on_xon, impl_.get());
  avr_irq_register_notify(avr_io_getirq(avr, AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_OUT_XOFF),
                          Impl::on_xoff, impl_.get());

  // ADC2: the MR sensor.
  impl_->adc2 = avr_io_getirq(avr, AVR_IOCTL_ADC_GETIRQ, ADC_IRQ_ADC2);
}

SimavrBoard::~SimavrBoard() {
  if (impl_ && impl_->avr != nullptr) {
    avr_terminate(impl_->avr);
    std::free(impl_->avr);
  }
}

void SimavrBoard::run_until(std::uint64_t cycle) noexcept {
  avr_t* avr = impl_->avr;
  impl_->pump();
  while (avr->cycle < cycle) {
    if (avr->cycle >= abort_at_cycle) std::abort();  // test hook: a board that dies mid-run
    const int state = avr_run(avr);
    if (state == cpu_Done || state == cpu_Crashed) {
      avr->cycle = cycle;  // a dead CPU: time passes, nothing runs
      break;
    }
  }
}

std::size_t SimavrBoard::to_board_pending() const noexcept { return impl_->to_board_count; }

std::uint64_t SimavrBoard::cycle() const noexcept { return impl_->avr->cycle; }

// counts = mV * 1023 / Vref (simavr truncates), so the smallest mV that reaches `counts`.
void SimavrBoard::set_sensor_counts(std::int32_t counts) noexcept {
  const std::int64_t clamped = counts < 0 ? 0 : (counts > 1023 ? 1023 : counts);
  const std::int64_t mV = (clamped * kVref_mV + 1022) / 1023;
  avr_raise_irq(impl_->adc2, static_cast<std::uint32_t>(mV));
}

// OC0B connected (non-inverting fast PWM): high for OCR0B + 1 of 256 counts; otherwise
// the pin is a plain output at the PORTD5 level.
double SimavrBoard::motor_duty() const noexcept {
  const std::uint8_t* data = impl_->avr->data;
  if ((data[kDdrD] & kPin5) == 0) return 0.0;  // an input pin drives nothing
  if (data[kTccr0A] & kCom0B1) return (data[kOcr0B] + 1.0) / 256.0;
  return (data[kPortD] & kPin5) ? 1.0 : 0.0;
}

bool SimavrBoard::direction_high() const noexcept {
  return (impl_->avr->data[kPortB] & 0x01) != 0;
}

bool SimavrBoard::send_byte(std::uint8_t byte) noexcept {
  Impl& impl = *impl_;
  if (impl.to_board_count == impl.to_board.size()) return false;
  impl.to_board[(impl.to_board_head + impl.to_board_count) % impl.to_board.size()] = byte;
  ++impl.to_board_count;
  return true;
}

std::size_t SimavrBoard::take_bytes(std::uint8_t* out, std::size_t capacity) noexcept {
  Impl& impl = *impl_;
  std::size_t n = 0;
  while (n < capacity && impl.to_host_count > 0) {
    out[n++] = impl.to_host[impl.to_host_head];
    impl.to_host_head = (impl.to_host_head + 1) % impl.to_host.size();
    --impl.to_host_count;
  }
  return n;
}

void SimavrBoard::reset() noexcept {
  avr_reset(impl_->avr);
  impl_->uart_blocked = false;
}

}  // namespace hapscene
