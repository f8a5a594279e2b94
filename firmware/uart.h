/* USART0 at HS_FIRMWARE_BAUD, 8N1, interrupt driven both ways through small rings, so
 * neither receiving nor sending ever waits. */
#ifndef HAPSCENE_FIRMWARE_UART_H
#define HAPSCENE_FIRMWARE_UART_H

#include <stdint.h>

void uart_init(void);

/* Takes one received byte; returns 0 when none is waiting. */
uint8_t uart_read(uint8_t* byte);

/* Queues `length` bytes whole, or none when the ring lacks room (returns 0). */
uint8_t uart_write(const uint8_t* data, uint8_t length);

#endif
