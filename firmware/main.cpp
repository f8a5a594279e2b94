/* hapscene firmware for the Hapkit 3.0 board (ATmega328P, avr-libc, no Arduino core).
 *
 * The board samples the MR sensor at 5 kHz from a timer interrupt and unwraps it, and
 * answers the host over the serial port with the protocol in protocol.h: HELLO arms it,
 * each COMMAND sets the PWM duty and direction and is answered with a STATE. Safety on
 * the board itself:
 *   - motor off at reset, and COMMANDs refused until a HELLO after every reset;
 *   - no valid COMMAND for HS_COMMAND_TIMEOUT_MS: motor off;
 *   - the duty never exceeds HS_DUTY_LIMIT;
 *   - the hardware watchdog resets the board (motor off) if the main loop stalls.
 */
#include <avr/interrupt.h>
#include <avr/io.h>
#include <avr/wdt.h>

#include "firmware/board.h"
#include "firmware/motor.h"
#include "firmware/sampler.h"
#include "firmware/uart.h"
#include "protocol/protocol.h"

/* Survives a reset (not cleared by the C runtime), so it changes at every boot. */
static uint8_t g_boot_counter __attribute__((section(".noinit")));
static uint8_t g_reset_cause __attribute__((section(".noinit")));

/* Runs before main and before the C runtime's initialisation: save the reset cause,
 * and stop a watchdog left running by a watchdog reset (it would fire again in 15 ms). */
extern "C" void early_reset(void) __attribute__((naked, used, section(".init3")));
extern "C" void early_reset(void) {
  g_reset_cause = MCUSR;
  MCUSR = 0;
  wdt_disable();
}

namespace {

/* Everything the main loop keeps between passes. */
struct Board {
  hs_decoder decoder;
  uint8_t armed;            /* a HELLO was accepted since reset */
  uint8_t tx_seq;           /* our sequence number */
  uint8_t rx_seq_expected;  /* the host's next sequence number */
  uint8_t rx_seq_known;
  uint8_t timed_out_flag;   /* reported once in the next STATE */
  uint8_t duty_limited_flag;
  uint16_t last_command_tick;
  hs_stats stats;
};

Board g_board;

/* Sends one frame; a full transmit ring drops it (the host counts the gap). */
void send_frame(uint8_t type, const uint8_t* payload, uint8_t length) {
  uint8_t frame[HS_MAX_FRAME];
  const uint8_t size = hs_encode_frame(type, g_board.tx_seq, payload, length, frame);
  if (size > 0 && uart_write(frame, size)) g_board.tx_seq = (uint8_t)(g_board.tx_seq + 1);
}

void send_refused(uint8_t type, uint8_t reason) {
  const uint8_t payload[2] = {type, reason};
  send_frame(HS_TYPE_REFUSED, payload, 2);
}

/* HELLO: check the protocol version, arm, and say who we are. */
void on_hello(const hs_frame& frame) {
  if (frame.length != 1 || frame.payload[0] != HS_PROTOCOL_VERSION) {
    send_refused(frame.type, HS_REFUSED_VERSION);
    return;
  }
  g_board.armed = 1;
  g_board.last_command_tick = sampler_ticks();
  hs_hello_reply reply;
  reply.protocol_version = HS_PROTOCOL_VERSION;
  reply.firmware_major = HS_FIRMWARE_VERSION_MAJOR;
  reply.firmware_minor = HS_FIRMWARE_VERSION_MINOR;
  reply.firmware_patch = HS_FIRMWARE_VERSION_PATCH;
  reply.board_kind = HS_BOARD_HAPKIT3;
  reply.signature[0] = SIGNATURE_0;
  reply.signature[1] = SIGNATURE_1;
  reply.signature[2] = SIGNATURE_2;
  reply.sample_rate_hz = HS_SAMPLE_RATE_HZ;
  reply.duty_limit = HS_DUTY_LIMIT;
  reply.timeout_ms = HS_COMMAND_TIMEOUT_MS;
  reply.reset_cause = g_reset_cause;
  reply.boot_id = g_boot_counter;
  reply.reserved = 0;
  uint8_t payload[HS_HELLO_REPLY_SIZE];
  hs_put_hello_reply(&reply, payload);
  send_frame(HS_TYPE_HELLO_REPLY, payload, HS_HELLO_REPLY_SIZE);
}

/* COMMAND: drive the motor (limited), restart the timeout, answer with the sensor. */
void on_command(const hs_frame& frame) {
  if (frame.length != HS_COMMAND_SIZE) {
    send_refused(frame.type, HS_REFUSED_BAD_LENGTH);
    return;
  }
  if (!g_board.armed) {
    send_refused(frame.type, HS_REFUSED_NOT_ARMED);
    return;
  }
  hs_command command;
  hs_get_command(frame.payload, &command);
  uint8_t duty = command.duty;
  if (duty > HS_DUTY_LIMIT) {
    duty = HS_DUTY_LIMIT;
    g_board.duty_limited_flag = 1;
  }
  if (command.flags & HS_COMMAND_ENABLE) {
    motor_drive(duty, (uint8_t)(command.flags & HS_COMMAND_DIRECTION_HIGH));
  } else {
    motor_off();
  }
  g_board.last_command_tick = sampler_ticks();

  const sampler_reading reading = sampler_latest();
  hs_state state;
  state.echo_seq = frame.seq;
  state.status = (uint8_t)((motor_is_on() ? HS_STATUS_MOTOR_ON : 0) | HS_STATUS_ARMED |
                           (g_board.timed_out_flag ? HS_STATUS_TIMED_OUT : 0) |
                           (g_board.duty_limited_flag ? HS_STATUS_DUTY_LIMITED : 0));
  state.raw_counts = reading.raw_counts;
  state.unwrapped_counts = reading.unwrapped_counts;
  state.sample_count = reading.sample_count;
  state.boot_id = g_boot_counter;
  state.reserved = 0;
  g_board.timed_out_flag = 0;
  g_board.duty_limited_flag = 0;
  uint8_t payload[HS_STATE_SIZE];
  hs_put_state(&state, payload);
  send_frame(HS_TYPE_STATE, payload, HS_STATE_SIZE);
}

void on_stats_request(void) {
  hs_stats stats = g_board.stats;
  stats.sampler_cycles_max = sampler_cycles_max();
  stats.frames_ok = g_board.decoder.frames_ok;
  stats.crc_errors = g_board.decoder.crc_errors;
  stats.length_errors = g_board.decoder.length_errors;
  stats.bytes_skipped = g_board.decoder.bytes_skipped;
  uint8_t payload[HS_STATS_SIZE];
  hs_put_stats(&stats, payload);
  send_frame(HS_TYPE_STATS, payload, HS_STATS_SIZE);
}

/* One valid frame from the host: count sequence gaps, then dispatch on its type. */
void on_frame(const hs_frame& frame) {
  if (g_board.rx_seq_known && frame.seq != g_board.rx_seq_expected) {
    g_board.stats.seq_gaps = (uint16_t)(g_board.stats.seq_gaps +
                                        (uint8_t)(frame.seq - g_board.rx_seq_expected));
  }
  g_board.rx_seq_known = 1;
  g_board.rx_seq_expected = (uint8_t)(frame.seq + 1);

  switch (frame.type) {
    case HS_TYPE_HELLO: on_hello(frame); break;
    case HS_TYPE_COMMAND: on_command(frame); break;
    case HS_TYPE_STATS_REQUEST: on_stats_request(); break;
    default: send_refused(frame.type, HS_REFUSED_UNKNOWN_TYPE); break;
  }
}

/* The command timeout: the host went quiet, so the motor goes off. */
void check_timeout(void) {
  if (!motor_is_on()) return;
  const uint16_t elapsed = (uint16_t)(sampler_ticks() - g_board.last_command_tick);
  if (elapsed >= HS_COMMAND_TIMEOUT_TICKS) {
    motor_off();
    g_board.timed_out_flag = 1;
    g_board.stats.timeouts = (uint16_t)(g_board.stats.timeouts + 1);
  }
}

}  // namespace

int main(void) {
  /* Motor off first, then the rest; the watchdog last, once everything is up. */
  motor_init();
  g_boot_counter = (uint8_t)(g_boot_counter + 1);
  hs_decoder_init(&g_board.decoder);
  uart_init();
  sampler_init();
  sei();
  wdt_enable(WDTO_30MS);

  uint32_t pass_start = sampler_now_cycles();
  for (;;) {
    wdt_reset();

    /* Decode whatever arrived and answer each frame. */
    uint8_t byte;
    while (uart_read(&byte)) {
      hs_decoder_push(&g_board.decoder, byte);
      hs_frame frame;
      while (hs_decoder_poll(&g_board.decoder, &frame)) on_frame(frame);
    }
    check_timeout();

    /* Time this pass of the loop in CPU cycles. */
    const uint32_t now = sampler_now_cycles();
    const uint32_t pass = now - pass_start;
    pass_start = now;
    const uint16_t pass16 = pass > 0xFFFFu ? 0xFFFFu : (uint16_t)pass;
    if (pass16 > g_board.stats.loop_cycles_max) g_board.stats.loop_cycles_max = pass16;
  }
}
