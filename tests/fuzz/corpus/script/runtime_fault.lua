-- fuzz seed: a fault only at run time (an undefined global beyond 10 mm)
params = { stiffness = "100 N/m" }
function force(s)
  if s.x > 0.01 then return undefined_gain * s.x end
  return -params.stiffness * s.x
end
