-- Sinusoidal grating: a position-based texture, F = -A sin(2 pi (x - x0) / lambda), the
-- slope of the potential U = -(A lambda / 2 pi) cos(2 pi (x - x0) / lambda). Conservative:
-- it depends on position only, so it feels the same at any speed and in either direction.
-- Feels like: running a finger over a fine washboard; each ridge resists and then pushes,
-- and the handle likes to rest in the grooves at x0 + k lambda. The steepest part has a
-- stiffness of A 2 pi / lambda (377 N/m with the defaults).
params = {
  amplitude = "0.3 N",    -- A
  wavelength = "5 mm",    -- lambda, ridge to ridge
  origin = "0 mm",        -- x0, a groove
}
needs = { velocity = false, time = false }

local A, lambda, x0 = params.amplitude, params.wavelength, params.origin
if lambda <= 0 then error("grating: wavelength must be positive") end
local k = 2 * math.pi / lambda
local sin = math.sin

function force(s)
  return -A * sin(k * (s.x - x0))
end
