/* The MR sensor sampler: a Timer1 compare interrupt at HS_SAMPLE_RATE_HZ reads the
 * conversion started by the previous interrupt, starts the next one and unwraps the
 * reading with the shared FlipCounter. Timer1 counts CPU cycles (prescaler 1), so it
 * also times the firmware. */
#ifndef HAPSCENE_FIRMWARE_SAMPLER_H
#define HAPSCENE_FIRMWARE_SAMPLER_H

#include <stdint.h>

typedef struct {
  uint16_t raw_counts;
  int32_t unwrapped_counts;
  uint16_t sample_count;
} sampler_reading;

/* Takes a first sample synchronously (so the flip counter starts from a real reading),
 * then starts the interrupt. Interrupts must be enabled by the caller. */
void sampler_init(void);

/* The latest sample, read atomically. */
sampler_reading sampler_latest(void);

/* Sampler ticks since reset (one per HS_SAMPLE_RATE_HZ period), read atomically. */
uint16_t sampler_ticks(void);

/* CPU cycles since reset (wraps after 268 s), read atomically. */
uint32_t sampler_now_cycles(void);

/* Longest interrupt so far, in CPU cycles from the compare match to its end. */
uint16_t sampler_cycles_max(void);

#endif
