// colcon-wasm: the throw-away executable whose link line is recorded as a
// library's link closure (see colcon_wasm/link/closure.py). It is never
// linked: the link launcher writes the closure instead.
int main() {return 0;}
