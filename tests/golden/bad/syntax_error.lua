function force(s)
  return -100 * s.x +
end
