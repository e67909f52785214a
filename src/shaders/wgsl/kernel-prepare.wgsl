// Single-invocation kernels that turn GPU-written queue lengths into indirect dispatch arguments,
// so bounces never wait on a CPU readback. dispatchArgs[0..3) drive extend/shade,
// dispatchArgs[4..7) drive shadow rays.
@compute @workgroup_size(1)
fn prepare_bounce() {
  let n = atomicLoad(&counters[bounce.inCounter]);
  dispatchArgs[0] = (n + WORKGROUP_SIZE - 1u) / WORKGROUP_SIZE;
  dispatchArgs[1] = 1u;
  dispatchArgs[2] = 1u;
  atomicStore(&counters[bounce.outCounter], 0u);
  atomicStore(&counters[COUNTER_SHADOW_COUNT], 0u);
}

@compute @workgroup_size(1)
fn prepare_shadow() {
  let n = atomicLoad(&counters[COUNTER_SHADOW_COUNT]);
  dispatchArgs[4] = (n + WORKGROUP_SIZE - 1u) / WORKGROUP_SIZE;
  dispatchArgs[5] = 1u;
  dispatchArgs[6] = 1u;
}
