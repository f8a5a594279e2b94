-- Vibration: a time-based sinusoidal force, F = A sin(2 pi f t), in bursts: on for
-- `pulse_on` at the start of every `pulse_period` (pulse_period = "0 s": continuous).
-- It does not depend on where the handle is.
-- Feels like: a phone buzzing in your hand, twice a second with the defaults. Keep f well
-- below half the loop rate (80 Hz at 1 kHz gives 12 samples per cycle).
params = {
  amplitude = "0.5 N",     -- A
  frequency = "80 Hz",     -- f
  pulse_period = "0.5 s",  -- a burst starts every pulse_period; "0 s" for no bursts
  pulse_on = "0.2 s",      -- how long each burst lasts
}
needs = { velocity = false }

local A, f, period, on = params.amplitude, params.frequency, params.pulse_period, params.pulse_on
if f < 0 or period < 0 or on < 0 then
  error("vibration: frequency, pulse_period and pulse_on must not be negative")
end
local sin, pi = math.sin, math.pi

function force(s)
  if period > 0 and s.t % period >= on then
    return 0
  end
  return A * sin(2 * pi * f * s.t)
end
