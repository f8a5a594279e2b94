#include "engine/devices/board_report.hpp"

#include "engine/base/format.hpp"

namespace hapscene {
namespace {

double us(std::uint64_t ns) { return static_cast<double>(ns) * 1e-3; }

}  // namespace

std::string board_report(const BoardLink& link, std::int64_t start_ns) {
  std::string out;
  // Who the board is.
  if (link.identified()) {
    const hs_hello_reply& id = link.identity();
    out += printf_string("  board            hapkit firmware %u.%u.%u, protocol %u, signature %02X %02X %02X, "
                  "sampling %u Hz, duty limit %u/255, timeout %u ms, reset cause 0x%02X\n",
                  id.firmware_major, id.firmware_minor, id.firmware_patch, id.protocol_version,
                  id.signature[0], id.signature[1], id.signature[2], id.sample_rate_hz,
                  id.duty_limit, id.timeout_ms, id.reset_cause);
  } else {
    out += "  board            never answered the handshake\n";
  }

  // What crossed the link, and what went wrong on the way.
  const LinkCounters& c = link.counters();
  const hs_decoder& d = link.decoder();
  out += printf_string("  link             %llu commands, %llu states; host saw %u CRC errors, %u bad lengths, "
                "%u bytes skipped, %llu lost frames, %llu stale reads\n",
                static_cast<unsigned long long>(c.commands_sent),
                static_cast<unsigned long long>(c.states_received), d.crc_errors, d.length_errors,
                d.bytes_skipped, static_cast<unsigned long long>(c.seq_gaps),
                static_cast<unsigned long long>(c.stale_reads));
  out += printf_string("  position         %llu ticks with no position yet, %llu stale (older than %.1f ms), "
                       "%llu after %llu implausible states: force held\n",
                       static_cast<unsigned long long>(c.unmeasured_polls),
                       static_cast<unsigned long long>(c.stale_polls),
                       static_cast<double>(link.config().max_position_age_ns) * 1e-6,
                       static_cast<unsigned long long>(c.implausible_polls),
                       static_cast<unsigned long long>(c.implausible_states));
  out += printf_string("  link health      %llu commands unanswered, %llu frames not sent whole; states said "
                       "command timeout %llu, duty limited %llu\n",
                       static_cast<unsigned long long>(c.unanswered),
                       static_cast<unsigned long long>(c.frames_dropped_tx),
                       static_cast<unsigned long long>(c.timeouts_reported),
                       static_cast<unsigned long long>(c.duty_limited));
  const LatencyHistogram& rtt = link.round_trip_ns();
  out += printf_string("  round trip       p50 %.1f us  p99 %.1f us  max %.1f us (%llu replies)\n",
                us(rtt.percentile_ns(0.50)), us(rtt.percentile_ns(0.99)), us(rtt.max_ns()),
                static_cast<unsigned long long>(rtt.count()));

  // The board's own view, from its last STATS frame.
  if (link.has_stats()) {
    const hs_stats& s = link.board_stats();
    out += printf_string("  firmware timing  sampler interrupt max %u cycles, main loop pass max %u cycles "
                  "(at 16 MHz: %.1f us, %.1f us)\n",
                  s.sampler_cycles_max, s.loop_cycles_max, s.sampler_cycles_max / 16.0,
                  s.loop_cycles_max / 16.0);
    out += printf_string("  board saw        %u frames, %u CRC errors, %u bad lengths, %u bytes skipped, "
                  "%u lost frames, %u command timeouts\n",
                  s.frames_ok, s.crc_errors, s.length_errors, s.bytes_skipped, s.seq_gaps, s.timeouts);
  }

  // Every fault event, in order.
  for (std::size_t i = 0; i < link.event_count(); ++i) {
    const LinkEvent& event = link.event(i);
    out += printf_string("  link event       %.3f s: %s\n",
                  static_cast<double>(event.t_ns - start_ns) * 1e-9, link_event_name(event.kind));
  }
  if (link.events_total() > link.event_count()) {
    out += printf_string("  link event       ... and %llu more\n",
                  static_cast<unsigned long long>(link.events_total() - link.event_count()));
  }
  return out;
}

std::string handshake_failure(const BoardLink& link) {
  const HandshakeSeen& seen = link.handshake_seen();
  const hs_decoder& d = link.decoder();
  std::string out;
  if (seen.other_version) {
    out = seen.version_known ? printf_string("the board answered with protocol version %u, this host speaks %u",
                                            seen.version, HS_PROTOCOL_VERSION)
                            : printf_string("the board refused protocol version %u", HS_PROTOCOL_VERSION);
    if (link.identified()) {
      const hs_hello_reply& id = link.identity();
      out += printf_string(" (firmware %u.%u.%u, board kind %u, signature %02X %02X %02X)", id.firmware_major,
                           id.firmware_minor, id.firmware_patch, id.board_kind, id.signature[0],
                           id.signature[1], id.signature[2]);
    }
    return out + ": flash the firmware built with this hapscene";
  }
  if (seen.bad_hello_replies > 0) {
    return printf_string("the board sent %llu HELLO_REPLY frames of the wrong length (not version %u's %u bytes)",
                         static_cast<unsigned long long>(seen.bad_hello_replies), HS_PROTOCOL_VERSION,
                         HS_HELLO_REPLY_SIZE);
  }
  if (seen.refused) {
    return printf_string("the board refused frame type 0x%02X (reason %u) and never answered the HELLO",
                         seen.refused_type, seen.refused_reason);
  }
  if (seen.frames > 0) {
    return printf_string("the board sent %llu valid frames (the last of type 0x%02X) but no HELLO_REPLY",
                         static_cast<unsigned long long>(seen.frames), seen.last_type);
  }
  if (d.bytes_skipped > 0 || d.crc_errors > 0 || d.length_errors > 0) {
    return printf_string("no valid frame: %u bytes skipped, %u CRC errors, %u bad lengths (a wrong baud rate, "
                         "or not the hapscene firmware?)",
                         d.bytes_skipped, d.crc_errors, d.length_errors);
  }
  return "no answer (nothing received)";
}

}  // namespace hapscene
