/* The motor driver: PWM duty on OC0B (D5) and the direction pin (D8). Off at reset. */
#ifndef HAPSCENE_FIRMWARE_MOTOR_H
#define HAPSCENE_FIRMWARE_MOTOR_H

#include <stdint.h>

/* Pins low, PWM disconnected, Timer0 in fast PWM at 62.5 kHz ready for a duty. */
void motor_init(void);

/* Duty level of 255: 0 off (pin low), 1..254 -> level/255 of the PWM period to the
 * nearest of its 256 counts, 255 full on. The caller applies the duty limit. */
void motor_drive(uint8_t level, uint8_t direction_high);

/* Pin low and PWM disconnected: no torque. */
void motor_off(void);

/* Whether the PWM output is driving the motor. */
uint8_t motor_is_on(void);

#endif
