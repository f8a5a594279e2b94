-- fuzz seed: most of the sandbox's API in one script
params = { k = "200 N/m", width = "3 mm", on = true, label = "tour" }
needs = { velocity = true, time = true }
local history = {}
local co = coroutine.wrap(function() local i = 0 while true do i = i + 1 coroutine.yield(i) end end)
function reset()
  history = {}
  math.randomseed(3)
end
function force(s)
  history[#history + 1] = s.x
  if #history > 16 then table.remove(history, 1) end
  local sorted = table.pack(table.unpack(history))
  table.sort(sorted, function(a, b) return a < b end)
  local text = string.format("%s %.3f %d", params.label, s.x, co())
  if s.t > 0.005 then log(text:upper(), #text, utf8.len("héllo")) end
  local ok, err = pcall(error, "caught")
  local mt = setmetatable({}, { __index = function(t, key) return 0 end, __len = function() return 2 end })
  local f = -params.k * (s.x - sorted[1]) - 0.5 * s.v + mt.anything + #mt * 0
  if s.x > params.width and params.on then f = f - math.sin(s.t * 2 * math.pi) end
  return f + collectgarbage("count") * 0 + string.rep("ab", 3, ","):len() * 0
end
