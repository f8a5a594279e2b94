-- Spring: the Hapkit lab spring, F = -K (x - x0).
-- Feels like: a rubber band tied to the centre. The further you push the handle, the
-- harder it pulls back; let go and it swings back (and oscillates if K is high and the
-- hand is light). Start soft (30 N/m); a few hundred N/m is stiff; too stiff buzzes or
-- makes the capstan cable slip.
params = {
  stiffness = "100 N/m",  -- K
  center = "0 mm",        -- x0, where the force is zero
}
needs = { velocity = false, time = false }

local K, x0 = params.stiffness, params.center

function force(s)
  return -K * (s.x - x0)
end
