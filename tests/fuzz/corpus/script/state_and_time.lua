-- fuzz seed: state carried between calls and time, as a virtual mass on a spring
params = { mass = "50 g", k = "300 N/m", b = "0.5 N*s/m" }
needs = { velocity = false, time = true }
local x, v = 0, 0
function reset() x, v = 0, 0 end
function force(s)
  local f = params.k * (s.x - x)
  v = v + (f - params.b * v) / params.mass * s.dt
  x = x + v * s.dt
  return -f
end
