#!/usr/bin/env python3
"""Writes the wire-protocol seed inputs in corpus/board_link and corpus/firmware_decoder:
valid frames (protocol/protocol.h: 0xA5, type, seq, length, payload, CRC-16/CCITT-FALSE)
in the input layouts that board_link_fuzz.cpp and firmware_decoder_fuzz.cpp read.
Run from anywhere: python3 tests/fuzz/frame_seeds.py"""
import os
import struct

here = os.path.join(os.path.dirname(os.path.abspath(__file__)), "corpus")


def crc16(data):
    crc = 0xFFFF
    for b in data:
        crc ^= b << 8
        for _ in range(8):
            crc = ((crc << 1) ^ 0x1021) & 0xFFFF if crc & 0x8000 else (crc << 1) & 0xFFFF
    return crc


assert crc16(b"123456789") == 0x29B1  # the CRC's published check value


def frame(frame_type, seq, payload=b""):
    body = bytes([frame_type, seq, len(payload)]) + payload
    return b"\xA5" + body + struct.pack("<H", crc16(body))


def state(echo, counts, status=2, boot=1):
    return bytes([echo, status]) + struct.pack("<HiHBB", counts & 1023, counts, 7, boot, 0)


hello_reply = bytes([1, 0, 1, 0, 1, 0x1E, 0x95, 0x0F]) + struct.pack("<H", 5000) + bytes([242, 20, 1, 1, 0])
stats = struct.pack("<8H", 300, 1500, 10, 0, 0, 0, 0, 0)
refused_not_armed = bytes([0x02, 1])
reply = frame(0x81, 0, hello_reply)
first_state = frame(0x82, 1, state(0, 500))


def write(folder, name, data):
    with open(os.path.join(here, folder, name), "wb") as out:
        out.write(data)


# board_link, raw mode: mode byte 0, then per tick a control byte (the byte count) and bytes;
# a tick given as a number is a bare control byte: 0x80 lets 100 ms pass, 0x40 fails the port.
def raw(ticks):
    out = b"\x00"
    for tick in ticks:
        out += bytes([tick]) if isinstance(tick, int) else bytes([len(tick)]) + tick
    return out


write("board_link", "raw_session", raw([b"", reply, first_state, frame(0x83, 2, stats),
                                        frame(0x82, 4, state(1, 510, 2 | 8)),
                                        b"\x00\xA5garbage" + first_state[:7], first_state[7:]]))
write("board_link", "raw_reset", raw([b"", reply, first_state, frame(0x8F, 3, refused_not_armed), b"",
                                      reply, frame(0x82, 1, state(2, 100, 2, 2))]))
write("board_link", "raw_other_version", raw([b"", frame(0x81, 5, bytes([2]) + hello_reply[1:]), b""]))
write("board_link", "raw_silence_vanish", raw([b"", reply, first_state, 0x80, 0x80, 0x40, 0xC0, 0x80, reply]))


# board_link, frame mode: mode byte 1, then per tick a control byte (frame count 0..3) and
# per frame (0x80 | index of HELLO_REPLY/STATE/STATS/REFUSED, seq, length, payload).
def fields(index, seq, payload):
    return bytes([0x80 | index, seq, len(payload)]) + payload


write("board_link", "frames_session",
      b"\x01" + bytes([0]) + bytes([3]) + fields(0, 0, hello_reply) + fields(1, 1, state(0, 500)) +
      fields(2, 2, stats) + bytes([2]) + fields(3, 3, refused_not_armed) + fields(0, 0, hello_reply) +
      bytes([1]) + fields(1, 1, state(3, -400)) + bytes([0x80, 0x40]))

# firmware_decoder: a byte choosing how often to poll (1 + b % 8 bytes), then what the host sends.
hello = frame(0x01, 0, bytes([1]))
command = frame(0x02, 1, bytes([128, 3]))
stats_request = frame(0x03, 2)
command2 = frame(0x02, 3, bytes([255, 2]))
corrupt = bytearray(command2)
corrupt[5] ^= 0x10
write("firmware_decoder", "host_session", bytes([0]) + hello + command + stats_request + command2)
write("firmware_decoder", "garbage_between",
      bytes([0]) + b"\xA5\xA5\xFF" + hello + b"\x00\xA5\x30" + command + bytes(corrupt) + command2)
write("firmware_decoder", "poll_every_8", bytes([7]) + hello + command + b"\xA5" * 40 + stats_request + command2)
write("firmware_decoder", "long_length", bytes([0]) + b"\xA5\x02\x00\xFF" + command)
