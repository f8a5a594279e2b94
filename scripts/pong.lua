-- Ball in a box (pong): a ball bounces between the walls of a box; the handle is a paddle
-- that can enter the box from the left. The ball stays on the paddle's right; when they
-- touch, a contact spring pushes the ball away and the hand back:
--   p = x - (xb - r) > 0:  ball pushed by +kp p, hand by F = -kp p;  otherwise F = 0
-- The walls reflect the ball with restitution e. Integrated with semi-implicit Euler in
-- substeps of at most 0.1 / sqrt(kp / m).
-- Feels like: a ball served at you; each time it comes back you feel a tap on the
-- paddle (about 0.7 N for 0.15 m/s), and the harder you hit it the faster it returns.
-- Push it against the far wall and it feels solid.
params = {
  left = "-40 mm",              -- the box's left wall
  right = "40 mm",              -- the box's right wall
  radius = "4 mm",              -- r, the ball's radius
  mass = "0.03 kg",             -- m, the ball's mass
  serve_position = "20 mm",     -- the ball's centre at the start
  serve_velocity = "-0.15 m/s", -- the ball's velocity at the start (negative: towards you)
  paddle_stiffness = "800 N/m", -- kp, paddle-ball contact
  restitution = 0.9,            -- e, of the walls (1: no loss)
}
needs = { velocity = false, time = false }

local left, right, r, m = params.left, params.right, params.radius, params.mass
local kp, e = params.paddle_stiffness, params.restitution
if right - left <= 2 * r or m <= 0 or kp <= 0 or e < 0 or e > 1 then
  error("pong: need a box wider than the ball, mass > 0, paddle_stiffness > 0, 0 <= restitution <= 1")
end
local max_step = 0.1 / math.sqrt(kp / m)
local ceil = math.ceil

local xb, vb  -- the ball's centre and velocity

function reset()
  xb, vb = params.serve_position, params.serve_velocity
end
reset()

-- Contact penetration of the paddle (at x) into the ball.
local function penetration(x)
  local p = x - (xb - r)
  return p > 0 and p or 0
end

function force(s)
  local x = s.x
  local steps = ceil(s.dt / max_step)
  if steps < 1 then steps = 1 end
  local h = s.dt / steps
  for _ = 1, steps do
    vb = vb + kp * penetration(x) / m * h
    xb = xb + vb * h
    if xb + r > right then
      xb, vb = right - r, -e * (vb > 0 and vb or -vb)
    elseif xb - r < left then
      xb, vb = left + r, e * (vb > 0 and vb or -vb)
    end
  end
  return -kp * penetration(x)
end
