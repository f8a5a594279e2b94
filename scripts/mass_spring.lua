-- Virtual mass on a spring: a mass m hangs on a spring k from `center`, and the hand
-- holds it through a coupling spring kc (a virtual coupling). The hand feels
-- F = -kc (x - xm); the mass obeys
--   m xm'' = kc (x - xm) - k (xm - x0) - b xm'
-- integrated here with semi-implicit (symplectic) Euler, which does not gain energy, in
-- substeps of at most 0.1 / omega (omega = sqrt((k + kc) / m)), so it stays stable and
-- accurate whatever the tick period.
-- Feels like: holding a heavy ball on a rubber band. Push and it lags behind, then
-- swings back; shake the handle near the natural frequency (about 7 Hz with the
-- defaults) and it resonates. Held still, it settles to the series spring
-- kc k / (kc + k) (75 N/m).
params = {
  mass = "0.2 kg",         -- m
  stiffness = "100 N/m",   -- k, from the mass to the centre
  coupling = "300 N/m",    -- kc, from the handle to the mass
  damping = "0.5 N*s/m",   -- b, on the mass
  center = "0 mm",         -- x0
}
needs = { velocity = false, time = false }

local m, k, kc, b, x0 = params.mass, params.stiffness, params.coupling, params.damping, params.center
if m <= 0 or k < 0 or kc <= 0 or b < 0 then
  error("mass_spring: need mass > 0, coupling > 0, stiffness >= 0, damping >= 0")
end
local max_step = 0.1 / math.sqrt((k + kc) / m)
local ceil = math.ceil

-- The mass's state. It starts where it would rest with the hand where the hand is, so
-- the run does not begin with a jolt.
local xm, vm, started

function reset()
  xm, vm, started = x0, 0, false
end
reset()

function force(s)
  local x = s.x
  if not started then
    xm, vm, started = (kc * x + k * x0) / (kc + k), 0, true
  end
  local steps = ceil(s.dt / max_step)
  if steps < 1 then steps = 1 end
  local h = s.dt / steps
  for _ = 1, steps do
    local a = (kc * (x - xm) - k * (xm - x0) - b * vm) / m
    vm = vm + a * h
    xm = xm + vm * h
  end
  return -kc * (x - xm)
end
