/* The wire protocol between the hapscene host and the Hapkit board: one header, shared
 * by the firmware (avr-gcc, C or C++) and the host (C++20). Plain C, stdint only, no
 * allocation, so it compiles everywhere and its decoder is unit tested on the host.
 *
 * Frame (all multi-byte values little-endian):
 *
 *   offset  size  field
 *   0       1     start byte 0xA5
 *   1       1     type (HS_TYPE_*)
 *   2       1     sequence number of the sender, +1 per frame sent (wraps at 256)
 *   3       1     payload length N (0..HS_MAX_PAYLOAD)
 *   4       N     payload
 *   4+N     2     CRC-16/CCITT-FALSE (poly 0x1021, init 0xFFFF) over bytes 1..3+N
 *
 * The decoder drops bytes until a start byte, refuses a length over HS_MAX_PAYLOAD and a
 * bad CRC by dropping that start byte and scanning on from the next one, so it resyncs
 * after garbage, a corrupt byte or a lost byte, and never needs more than one frame of
 * buffer. Frames lost whole show up as gaps in the sequence numbers.
 */
#ifndef HAPSCENE_FIRMWARE_PROTOCOL_H
#define HAPSCENE_FIRMWARE_PROTOCOL_H

#include <stdint.h>
#include <string.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Version of this protocol; the board refuses a HELLO with another one. */
#define HS_PROTOCOL_VERSION 1

#define HS_START_BYTE 0xA5
#define HS_HEADER_SIZE 4
#define HS_CRC_SIZE 2
#define HS_MAX_PAYLOAD 24
#define HS_MAX_FRAME (HS_HEADER_SIZE + HS_MAX_PAYLOAD + HS_CRC_SIZE)

/* Frame types: host -> board below 0x80, board -> host from 0x80. */
#define HS_TYPE_HELLO 0x01       /* payload: protocol version (1) */
#define HS_TYPE_COMMAND 0x02     /* payload: hs_command (2) */
#define HS_TYPE_STATS_REQUEST 0x03 /* payload: none */
#define HS_TYPE_HELLO_REPLY 0x81 /* payload: hs_hello_reply (15) */
#define HS_TYPE_STATE 0x82       /* payload: hs_state (12) */
#define HS_TYPE_STATS 0x83       /* payload: hs_stats (16) */
#define HS_TYPE_REFUSED 0x8F     /* payload: the refused type, the reason (2) */

/* Board kinds reported in the handshake. */
#define HS_BOARD_HAPKIT3 1

/* hs_command.flags */
#define HS_COMMAND_DIRECTION_HIGH 0x01 /* level of the direction pin */
#define HS_COMMAND_ENABLE 0x02         /* motor may be driven; clear: motor off */

/* hs_state.status */
#define HS_STATUS_MOTOR_ON 0x01      /* the PWM output is driving the motor */
#define HS_STATUS_ARMED 0x02         /* a HELLO was accepted since the board's reset */
#define HS_STATUS_TIMED_OUT 0x04     /* the command timeout switched the motor off since the last STATE */
#define HS_STATUS_DUTY_LIMITED 0x08  /* the last command's duty was above the board's limit */

/* HS_TYPE_REFUSED reasons */
#define HS_REFUSED_NOT_ARMED 1       /* COMMAND before HELLO (after a reset): motor stays off */
#define HS_REFUSED_VERSION 2         /* HELLO with another protocol version */
#define HS_REFUSED_UNKNOWN_TYPE 3
#define HS_REFUSED_BAD_LENGTH 4

/* Host -> board: drive the motor until the next command or the timeout. */
typedef struct {
  uint8_t duty;   /* 0..255 of full PWM duty */
  uint8_t flags;  /* HS_COMMAND_* */
} hs_command;

/* Board -> host, the answer to every COMMAND. */
typedef struct {
  uint8_t echo_seq;        /* sequence number of the COMMAND answered */
  uint8_t status;          /* HS_STATUS_* */
  uint16_t raw_counts;     /* latest MR sensor sample, 10-bit ADC counts */
  int32_t unwrapped_counts; /* raw + flips * span, counted by the board at its sample rate */
  uint16_t sample_count;   /* samples taken since reset (wraps) */
  uint8_t boot_id;         /* changes at every reset of the board */
  uint8_t reserved;
} hs_state;

/* Board -> host, the answer to HELLO: who the board is. */
typedef struct {
  uint8_t protocol_version;
  uint8_t firmware_major, firmware_minor, firmware_patch;
  uint8_t board_kind;      /* HS_BOARD_* */
  uint8_t signature[3];    /* the MCU's device signature (1E 95 0F: ATmega328P) */
  uint16_t sample_rate_hz; /* MR sensor sampling rate */
  uint8_t duty_limit;      /* highest duty the board applies, of 255 */
  uint8_t timeout_ms;      /* no valid command for this long: motor off */
  uint8_t reset_cause;     /* MCUSR at reset: 1 power-on, 2 external, 4 brown-out, 8 watchdog */
  uint8_t boot_id;
  uint8_t reserved;
} hs_hello_reply;

/* Board -> host, the answer to STATS_REQUEST: health and timing in CPU cycles. */
typedef struct {
  uint16_t sampler_cycles_max;  /* longest sensor interrupt, CPU cycles */
  uint16_t loop_cycles_max;     /* longest main-loop pass, CPU cycles */
  uint16_t frames_ok;           /* valid frames received */
  uint16_t crc_errors;          /* frames dropped for a bad CRC */
  uint16_t bytes_skipped;       /* bytes dropped while hunting for a frame */
  uint16_t seq_gaps;            /* host frames missing by sequence number */
  uint16_t timeouts;            /* times the command timeout switched the motor off */
  uint16_t length_errors;       /* frames dropped for a length over the maximum */
} hs_stats;

/* CRC-16/CCITT-FALSE, one byte at a time without a table or a bit loop (the shift-xor
 * form of polynomial 0x1021, as avr-libc's _crc_xmodem_update): about 30 AVR cycles. */
static inline uint16_t hs_crc16_update(uint16_t crc, uint8_t byte) {
  crc = (uint16_t)((uint16_t)(crc >> 8) | (uint16_t)(crc << 8));
  crc = (uint16_t)(crc ^ byte);
  crc = (uint16_t)(crc ^ (uint16_t)((crc & 0xFFu) >> 4));
  crc = (uint16_t)(crc ^ (uint16_t)(crc << 12));
  crc = (uint16_t)(crc ^ (uint16_t)((crc & 0xFFu) << 5));
  return crc;
}

static inline uint16_t hs_crc16(const uint8_t* data, uint8_t length) {
  uint16_t crc = 0xFFFFu;
  for (uint8_t i = 0; i < length; ++i) crc = hs_crc16_update(crc, data[i]);
  return crc;
}

/* Little-endian field access. */
static inline void hs_put_u16(uint8_t* at, uint16_t v) {
  at[0] = (uint8_t)(v & 0xFFu);
  at[1] = (uint8_t)(v >> 8);
}
static inline uint16_t hs_get_u16(const uint8_t* at) {
  return (uint16_t)(at[0] | (uint16_t)((uint16_t)at[1] << 8));
}
static inline void hs_put_u32(uint8_t* at, uint32_t v) {
  hs_put_u16(at, (uint16_t)(v & 0xFFFFu));
  hs_put_u16(at + 2, (uint16_t)(v >> 16));
}
static inline uint32_t hs_get_u32(const uint8_t* at) {
  return (uint32_t)hs_get_u16(at) | ((uint32_t)hs_get_u16(at + 2) << 16);
}

/* Writes a whole frame into `out` (at least HS_MAX_FRAME bytes); returns its size, or 0
 * when the payload is too long. */
static inline uint8_t hs_encode_frame(uint8_t type, uint8_t seq, const uint8_t* payload,
                                      uint8_t length, uint8_t* out) {
  if (length > HS_MAX_PAYLOAD) return 0;
  out[0] = HS_START_BYTE;
  out[1] = type;
  out[2] = seq;
  out[3] = length;
  if (length > 0) memcpy(out + HS_HEADER_SIZE, payload, length);
  hs_put_u16(out + HS_HEADER_SIZE + length, hs_crc16(out + 1, (uint8_t)(3 + length)));
  return (uint8_t)(HS_HEADER_SIZE + length + HS_CRC_SIZE);
}

/* Payload encoders and decoders: fixed sizes, field by field (no struct layout on the
 * wire, so the board's and the host's compilers need not agree on padding). */
#define HS_COMMAND_SIZE 2
#define HS_STATE_SIZE 12
#define HS_HELLO_REPLY_SIZE 15
#define HS_STATS_SIZE 16

static inline void hs_put_command(const hs_command* c, uint8_t* out) {
  out[0] = c->duty;
  out[1] = c->flags;
}
static inline void hs_get_command(const uint8_t* in, hs_command* c) {
  c->duty = in[0];
  c->flags = in[1];
}

static inline void hs_put_state(const hs_state* s, uint8_t* out) {
  out[0] = s->echo_seq;
  out[1] = s->status;
  hs_put_u16(out + 2, s->raw_counts);
  hs_put_u32(out + 4, (uint32_t)s->unwrapped_counts);
  hs_put_u16(out + 8, s->sample_count);
  out[10] = s->boot_id;
  out[11] = s->reserved;
}
static inline void hs_get_state(const uint8_t* in, hs_state* s) {
  s->echo_seq = in[0];
  s->status = in[1];
  s->raw_counts = hs_get_u16(in + 2);
  s->unwrapped_counts = (int32_t)hs_get_u32(in + 4);
  s->sample_count = hs_get_u16(in + 8);
  s->boot_id = in[10];
  s->reserved = in[11];
}

static inline void hs_put_hello_reply(const hs_hello_reply* h, uint8_t* out) {
  out[0] = h->protocol_version;
  out[1] = h->firmware_major;
  out[2] = h->firmware_minor;
  out[3] = h->firmware_patch;
  out[4] = h->board_kind;
  out[5] = h->signature[0];
  out[6] = h->signature[1];
  out[7] = h->signature[2];
  hs_put_u16(out + 8, h->sample_rate_hz);
  out[10] = h->duty_limit;
  out[11] = h->timeout_ms;
  out[12] = h->reset_cause;
  out[13] = h->boot_id;
  out[14] = h->reserved;
}
static inline void hs_get_hello_reply(const uint8_t* in, hs_hello_reply* h) {
  h->protocol_version = in[0];
  h->firmware_major = in[1];
  h->firmware_minor = in[2];
  h->firmware_patch = in[3];
  h->board_kind = in[4];
  h->signature[0] = in[5];
  h->signature[1] = in[6];
  h->signature[2] = in[7];
  h->sample_rate_hz = hs_get_u16(in + 8);
  h->duty_limit = in[10];
  h->timeout_ms = in[11];
  h->reset_cause = in[12];
  h->boot_id = in[13];
  h->reserved = in[14];
}

static inline void hs_put_stats(const hs_stats* s, uint8_t* out) {
  hs_put_u16(out + 0, s->sampler_cycles_max);
  hs_put_u16(out + 2, s->loop_cycles_max);
  hs_put_u16(out + 4, s->frames_ok);
  hs_put_u16(out + 6, s->crc_errors);
  hs_put_u16(out + 8, s->bytes_skipped);
  hs_put_u16(out + 10, s->seq_gaps);
  hs_put_u16(out + 12, s->timeouts);
  hs_put_u16(out + 14, s->length_errors);
}
static inline void hs_get_stats(const uint8_t* in, hs_stats* s) {
  s->sampler_cycles_max = hs_get_u16(in + 0);
  s->loop_cycles_max = hs_get_u16(in + 2);
  s->frames_ok = hs_get_u16(in + 4);
  s->crc_errors = hs_get_u16(in + 6);
  s->bytes_skipped = hs_get_u16(in + 8);
  s->seq_gaps = hs_get_u16(in + 10);
  s->timeouts = hs_get_u16(in + 12);
  s->length_errors = hs_get_u16(in + 14);
}

/* A decoded frame. */
typedef struct {
  uint8_t type;
  uint8_t seq;
  uint8_t length;
  uint8_t payload[HS_MAX_PAYLOAD];
} hs_frame;

/* The streaming decoder: push every received byte, then poll until it returns 0. */
typedef struct {
  uint8_t buffer[HS_MAX_FRAME];
  uint8_t count;
  /* Counters (wrap): what was dropped, and why. */
  uint16_t frames_ok;
  uint16_t crc_errors;
  uint16_t length_errors;
  uint16_t bytes_skipped;
} hs_decoder;

static inline void hs_decoder_init(hs_decoder* d) { memset(d, 0, sizeof(*d)); }

/* Drops the first `n` buffered bytes. */
static inline void hs_decoder_drop(hs_decoder* d, uint8_t n) {
  memmove(d->buffer, d->buffer + n, (size_t)(d->count - n));
  d->count = (uint8_t)(d->count - n);
}

/* Appends one byte. The buffer cannot overflow when hs_decoder_poll runs after each
 * push (a full buffer always holds a decidable frame); if it would, the oldest byte goes. */
static inline void hs_decoder_push(hs_decoder* d, uint8_t byte) {
  if (d->count == HS_MAX_FRAME) {
    hs_decoder_drop(d, 1);
    ++d->bytes_skipped;
  }
  d->buffer[d->count++] = byte;
}

/* Returns 1 and fills `frame` when a valid frame is complete; 0 when more bytes are
 * needed. Garbage before a start byte, over-long lengths and bad CRCs are counted and
 * skipped, scanning on from the byte after the rejected start byte. */
static inline int hs_decoder_poll(hs_decoder* d, hs_frame* frame) {
  for (;;) {
    /* Hunt for a start byte. */
    uint8_t first = 0;
    while (first < d->count && d->buffer[first] != HS_START_BYTE) ++first;
    if (first > 0) {
      d->bytes_skipped = (uint16_t)(d->bytes_skipped + first);
      hs_decoder_drop(d, first);
    }
    if (d->count < HS_HEADER_SIZE) return 0;

    /* A length over the maximum: not a frame start after all. */
    const uint8_t length = d->buffer[3];
    if (length > HS_MAX_PAYLOAD) {
      ++d->length_errors;
      ++d->bytes_skipped;
      hs_decoder_drop(d, 1);
      continue;
    }
    const uint8_t size = (uint8_t)(HS_HEADER_SIZE + length + HS_CRC_SIZE);
    if (d->count < size) return 0;

    /* Check the CRC; a mismatch drops only the start byte and scans on. */
    const uint16_t expected = hs_get_u16(d->buffer + HS_HEADER_SIZE + length);
    if (hs_crc16(d->buffer + 1, (uint8_t)(3 + length)) != expected) {
      ++d->crc_errors;
      ++d->bytes_skipped;
      hs_decoder_drop(d, 1);
      continue;
    }
    frame->type = d->buffer[1];
    frame->seq = d->buffer[2];
    frame->length = length;
    if (length > 0) memcpy(frame->payload, d->buffer + HS_HEADER_SIZE, length);
    ++d->frames_ok;
    hs_decoder_drop(d, size);
    return 1;
  }
}

#ifdef __cplusplus
}
#endif

#endif /* HAPSCENE_FIRMWARE_PROTOCOL_H */
