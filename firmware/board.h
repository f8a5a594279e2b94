/* The Hapkit 3.0 board as the firmware sees it: clock, pins, rates and limits.
 * ATmega328P at 16 MHz (Arduino Uno compatible).
 *   motor PWM      D5 = PD5 = OC0B, Timer0 fast PWM, prescaler 1: 62.5 kHz
 *   motor direction D8 = PB0
 *   MR sensor      A2 = ADC2 (10-bit, AVcc reference)
 *   serial         USART0 (D0/D1, the USB bridge), HS_FIRMWARE_BAUD, 8N1
 */
#ifndef HAPSCENE_FIRMWARE_BOARD_H
#define HAPSCENE_FIRMWARE_BOARD_H

#include <stdint.h>

#ifndef F_CPU
#define F_CPU 16000000UL
#endif

/* Serial speed; 1 Mbaud is exact at 16 MHz with U2X (UBRR = 1). */
#ifndef HS_FIRMWARE_BAUD
#define HS_FIRMWARE_BAUD 1000000UL
#endif

/* Firmware version, reported in the handshake (set by CMake from the project version). */
#ifndef HS_FIRMWARE_VERSION_MAJOR
#define HS_FIRMWARE_VERSION_MAJOR 0
#define HS_FIRMWARE_VERSION_MINOR 1
#define HS_FIRMWARE_VERSION_PATCH 0
#endif

/* MR sensor sampling from the Timer1 interrupt: 5 kHz, five times the host's 1 kHz loop.
 * One ADC conversion at prescaler 128 takes 104 us, inside the 200 us period. */
#define HS_SAMPLE_RATE_HZ 5000u
#define HS_SAMPLE_PERIOD_CYCLES ((uint16_t)(F_CPU / HS_SAMPLE_RATE_HZ))

/* No valid COMMAND for this long: motor off (counted in sampler ticks). */
#define HS_COMMAND_TIMEOUT_MS 20u
/* (32-bit arithmetic: int is 16 bits on the AVR, and 20 * 5000 overflows it.) */
#define HS_COMMAND_TIMEOUT_TICKS ((uint16_t)(HS_COMMAND_TIMEOUT_MS * (uint32_t)HS_SAMPLE_RATE_HZ / 1000u))

/* Highest duty the board applies whatever the host asks (242/255, 95 %). */
#define HS_DUTY_LIMIT 242u

/* The MR sensor's wrap-around, as in the hapkit3 profile. */
#define HS_FLIP_THRESHOLD_COUNTS 700
#define HS_SPAN_COUNTS 922

#endif /* HAPSCENE_FIRMWARE_BOARD_H */
