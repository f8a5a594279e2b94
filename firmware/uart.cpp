#include "firmware/uart.h"

#include <avr/interrupt.h>
#include <avr/io.h>

#include "firmware/board.h"

/* Power-of-two rings: the index arithmetic wraps by masking. */
#define RX_SIZE 64u
#define TX_SIZE 128u

static volatile uint8_t g_rx[RX_SIZE];
static volatile uint8_t g_rx_head, g_rx_tail;  /* head: written by the ISR */
static volatile uint8_t g_tx[TX_SIZE];
static volatile uint8_t g_tx_head, g_tx_tail;  /* tail: advanced by the ISR */

void uart_init(void) {
  /* Double speed: UBRR = F_CPU / (8 * baud) - 1, exact for 1 Mbaud at 16 MHz. */
  /* U2X before UBRR: simavr derives its byte timing when UBRR is written. */
  const uint16_t ubrr = (uint16_t)(F_CPU / (8UL * HS_FIRMWARE_BAUD) - 1UL);
  UCSR0A = _BV(U2X0);
  UBRR0H = (uint8_t)(ubrr >> 8);
  UBRR0L = (uint8_t)ubrr;
  UCSR0C = _BV(UCSZ01) | _BV(UCSZ00);
  UCSR0B = _BV(RXEN0) | _BV(TXEN0) | _BV(RXCIE0);
}

ISR(USART_RX_vect) {
  const uint8_t byte = UDR0;
  const uint8_t next = (uint8_t)((g_rx_head + 1u) & (RX_SIZE - 1u));
  if (next == g_rx_tail) return;  /* ring full: the byte is lost, the decoder resyncs */
  g_rx[g_rx_head] = byte;
  g_rx_head = next;
}

ISR(USART_UDRE_vect) {
  if (g_tx_tail == g_tx_head) {
    UCSR0B &= (uint8_t)~_BV(UDRIE0);  /* nothing left: stop asking */
    return;
  }
  UDR0 = g_tx[g_tx_tail];
  g_tx_tail = (uint8_t)((g_tx_tail + 1u) & (TX_SIZE - 1u));
}

uint8_t uart_read(uint8_t* byte) {
  if (g_rx_tail == g_rx_head) return 0;
  *byte = g_rx[g_rx_tail];
  g_rx_tail = (uint8_t)((g_rx_tail + 1u) & (RX_SIZE - 1u));
  return 1;
}

uint8_t uart_write(const uint8_t* data, uint8_t length) {
  const uint8_t used = (uint8_t)((g_tx_head - g_tx_tail) & (TX_SIZE - 1u));
  if ((uint16_t)used + length >= TX_SIZE) return 0;
  uint8_t head = g_tx_head;
  for (uint8_t i = 0; i < length; ++i) {
    g_tx[head] = data[i];
    head = (uint8_t)((head + 1u) & (TX_SIZE - 1u));
  }
  g_tx_head = head;
  UCSR0B |= _BV(UDRIE0);  /* the ISR sends from here on */
  return 1;
}
