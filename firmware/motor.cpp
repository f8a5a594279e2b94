#include "firmware/motor.h"

#include <avr/io.h>

#include "firmware/board.h"

static uint8_t g_motor_on;

void motor_init(void) {
  /* Outputs driven low before anything else: the motor stays off. */
  PORTD &= (uint8_t)~_BV(PD5);
  DDRD |= _BV(PD5);
  PORTB &= (uint8_t)~_BV(PB0);
  DDRB |= _BV(PB0);
  /* Timer0: fast PWM (WGM01:0), prescaler 1, OC0B disconnected until driven. */
  OCR0B = 0;
  TCCR0A = _BV(WGM01) | _BV(WGM00);
  TCCR0B = _BV(CS00);
  g_motor_on = 0;
}

void motor_off(void) {
  TCCR0A = _BV(WGM01) | _BV(WGM00);  /* OC0B disconnected: the pin follows PORTD5 */
  PORTD &= (uint8_t)~_BV(PD5);
  g_motor_on = 0;
}

void motor_drive(uint8_t level, uint8_t direction_high) {
  /* Direction first, so the new duty never drives the old direction. */
  if (direction_high) PORTB |= _BV(PB0);
  else PORTB &= (uint8_t)~_BV(PB0);

  if (level == 0) {
    motor_off();
    return;
  }
  if (level == 255) {
    /* Full on: a plain high pin (fast PWM cannot reach 100 %). */
    TCCR0A = _BV(WGM01) | _BV(WGM00);
    PORTD |= _BV(PD5);
  } else {
    /* Non-inverting fast PWM: high for OCR0B + 1 of 256 timer counts; level/255 of the
     * period to the nearest count is level + 1 counts from level 128 on. */
    OCR0B = (uint8_t)(level - 1 + (level >= 128 ? 1 : 0));
    TCCR0A = _BV(COM0B1) | _BV(WGM01) | _BV(WGM00);
  }
  g_motor_on = 1;
}

uint8_t motor_is_on(void) { return g_motor_on; }
