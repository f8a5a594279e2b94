local k = 100
function push(s) return -k * s.x end
