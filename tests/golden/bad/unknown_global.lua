function force(s)
  return -stiffness * s.x
end
