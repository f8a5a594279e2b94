#include "firmware/sampler.h"

#include <avr/interrupt.h>
#include <avr/io.h>
#include <util/atomic.h>

#include "firmware/board.h"
#include "protocol/flip_counter.hpp"

/* Written by the interrupt, read by the main loop with interrupts off. */
static hapscene::FlipCounter g_flips;
static volatile uint16_t g_raw_counts;
static volatile int32_t g_unwrapped_counts;
static volatile uint16_t g_sample_count;
static volatile uint32_t g_ticks;  /* 32 bits so cycle differences wrap cleanly */
static volatile uint16_t g_cycles_max;

/* One conversion of ADC2, waiting for it (only at start-up). */
static uint16_t convert_blocking(void) {
  ADCSRA |= _BV(ADSC);
  while (ADCSRA & _BV(ADSC)) {
  }
  return ADC;
}

void sampler_init(void) {
  /* ADC: AVcc reference, channel 2 (A2), prescaler 128 (125 kHz ADC clock). */
  ADMUX = _BV(REFS0) | 2;
  ADCSRA = _BV(ADEN) | _BV(ADPS2) | _BV(ADPS1) | _BV(ADPS0);
  DIDR0 = _BV(ADC2D);
  convert_blocking();  /* the first conversion after enabling is a long one; discard */

  /* Seed the flip counter with a real reading. */
  g_flips.threshold_counts = HS_FLIP_THRESHOLD_COUNTS;
  g_flips.span_counts = HS_SPAN_COUNTS;
  const uint16_t first = convert_blocking();
  g_raw_counts = first;
  g_unwrapped_counts = g_flips.update((int32_t)first);
  g_sample_count = 1;
  ADCSRA |= _BV(ADSC);  /* the next conversion, read by the first interrupt */

  /* Timer1: CTC on OCR1A, prescaler 1, so TCNT1 counts CPU cycles within a period. */
  TCCR1A = 0;
  TCNT1 = 0;
  OCR1A = (uint16_t)(HS_SAMPLE_PERIOD_CYCLES - 1);
  TCCR1B = _BV(WGM12) | _BV(CS10);
  TIMSK1 = _BV(OCIE1A);
}

ISR(TIMER1_COMPA_vect) {
  /* Read the finished conversion and start the next. */
  const uint16_t raw = ADC;
  ADCSRA |= _BV(ADSC);

  /* Unwrap and publish. */
  g_raw_counts = raw;
  g_unwrapped_counts = g_flips.update((int32_t)raw);
  g_sample_count = (uint16_t)(g_sample_count + 1);
  g_ticks = g_ticks + 1;

  /* Time this interrupt: TCNT1 restarted at 0 on the compare match. */
  const uint16_t cycles = TCNT1;
  if (cycles > g_cycles_max) g_cycles_max = cycles;
}

sampler_reading sampler_latest(void) {
  sampler_reading reading;
  ATOMIC_BLOCK(ATOMIC_RESTORESTATE) {
    reading.raw_counts = g_raw_counts;
    reading.unwrapped_counts = g_unwrapped_counts;
    reading.sample_count = g_sample_count;
  }
  return reading;
}

uint16_t sampler_ticks(void) {
  uint16_t ticks;
  ATOMIC_BLOCK(ATOMIC_RESTORESTATE) { ticks = (uint16_t)g_ticks; }
  return ticks;
}

uint32_t sampler_now_cycles(void) {
  uint32_t ticks;
  uint16_t within;
  ATOMIC_BLOCK(ATOMIC_RESTORESTATE) {
    ticks = g_ticks;
    within = TCNT1;
    /* A compare match not yet serviced: the counter restarted but ticks lag by one. */
    if ((TIFR1 & _BV(OCF1A)) && within < HS_SAMPLE_PERIOD_CYCLES / 2) ++ticks;
  }
  return ticks * HS_SAMPLE_PERIOD_CYCLES + within;
}

uint16_t sampler_cycles_max(void) {
  uint16_t cycles;
  ATOMIC_BLOCK(ATOMIC_RESTORESTATE) { cycles = g_cycles_max; }
  return cycles;
}
