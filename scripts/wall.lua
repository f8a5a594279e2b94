-- Hard wall: a stiff spring with damping on one side of `position`, plus an event-based
-- contact transient (Kuchenbecker et al. 2006): on each impact a decaying sinusoid
-- proportional to the impact speed is added, which is what makes a virtual wall feel
-- like a hard surface instead of a soft cushion.
--   inside (penetration p = n (x - xw) > 0, n = +1 for side "positive"):
--     F = -n K p - B v (B only while moving into the wall, so it never pulls)
--         - n A vi exp(-tau / td) sin(2 pi f tau)   (tau: time since impact,
--                                                      vi: impact speed, A vi <= Fmax)
--   outside: F = 0
-- Feels like: tapping a table top: a crisp "tock" on contact, then a firm surface.
-- Do not start the run with the handle inside the wall (the soft start helps, but the
-- first contact then has no transient).
params = {
  position = "10 mm",             -- xw, the wall surface
  side = "positive",              -- the solid side: "positive" (x > xw) or "negative"
  stiffness = "600 N/m",          -- K
  damping = "0.5 N*s/m",          -- B
  transient_gain = "15 N*s/m",    -- A, transient amplitude per m/s of impact speed
  transient_frequency = "150 Hz", -- f
  transient_decay = "15 ms",      -- td, time constant of the decay
  max_transient = "1.5 N",        -- Fmax, largest transient amplitude (keeps the
                                  -- first-millisecond step under the capstan slip limit)
}

local xw, K, B = params.position, params.stiffness, params.damping
local A, f, td, Fmax = params.transient_gain, params.transient_frequency,
                       params.transient_decay, params.max_transient
local n
if params.side == "positive" then
  n = 1
elseif params.side == "negative" then
  n = -1
else
  error("wall: side must be \"positive\" or \"negative\", got \"" .. params.side .. "\"")
end
local exp, sin, min, pi = math.exp, math.sin, math.min, math.pi

-- Contact state: was the handle inside at the last call, and the current transient.
local was_inside, impact_t, amplitude

function reset()
  was_inside, impact_t, amplitude = nil, 0, 0
end
reset()

function force(s)
  local p = n * (s.x - xw)
  local inside = p > 0
  if not inside then
    was_inside = false
    amplitude = 0
    return 0
  end
  -- An impact: outside at the last call, inside now, moving in.
  local speed_in = n * s.v
  if was_inside == false and speed_in > 0 then
    impact_t = s.t
    amplitude = min(A * speed_in, Fmax)
  end
  was_inside = true

  local f_spring = -n * K * p
  local f_damping = speed_in > 0 and -B * s.v or 0
  local f_transient = 0
  local tau = s.t - impact_t
  if amplitude > 0 and tau < 5 * td then
    f_transient = -n * amplitude * exp(-tau / td) * sin(2 * pi * f * tau)
  end
  return f_spring + f_damping + f_transient
end
