// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// sensor_msgs/PointCloud2 and LaserScan as typed arrays: the points' x, y, z
// read straight from the message's byte blob (no per-point objects), and a
// colour per point from its rgb/rgba field, its intensity or an axis, as
// rviz's colour transformers do. Plain JS: the page runs it on the main
// thread or in a worker alike.

// sensor_msgs/PointField datatypes
const READERS = {
  1: ['getInt8', 1], 2: ['getUint8', 1], 3: ['getInt16', 2], 4: ['getUint16', 2],
  5: ['getInt32', 4], 6: ['getUint32', 4], 7: ['getFloat32', 4], 8: ['getFloat64', 8],
};

/** The colour transformers of the PointCloud2 display. */
export const COLOR_MODES = ['RGB8', 'Intensity', 'AxisColor', 'FlatColor'];

function field(cloud, name) {
  return (cloud.fields || []).find((f) => f.name === name) || null;
}

/** A rainbow colour of t in [0, 1] (rviz's intensity/axis colouring). */
export function rainbow(t, out, i) {
  const h = (1 - Math.min(1, Math.max(0, t))) * 4;
  const x = 1 - Math.abs((h % 2) - 1);
  let r = 0; let g = 0; let b = 0;
  if (h < 1) { r = 1; g = x; } else if (h < 2) { r = x; g = 1; } else if (h < 3) { g = 1; b = x; } else { g = x; b = 1; }
  out[i] = r; out[i + 1] = g; out[i + 2] = b;
}

/**
 * Decode a PointCloud2: {count, positions: Float32Array(3n), colors: Float32Array(3n)|null, error}.
 * Points with a NaN coordinate are left out, as rviz leaves them out.
 */
export function decodeCloud(cloud, { mode = 'RGB8', axis = 2, flat = [1, 1, 1] } = {}) {
  const fx = field(cloud, 'x'); const fy = field(cloud, 'y'); const fz = field(cloud, 'z');
  if (!fx || !fy || !fz) return { count: 0, positions: new Float32Array(0), colors: null, error: 'the cloud has no x, y and z fields' };
  const n = cloud.width * cloud.height;
  const step = cloud.point_step;
  const data = cloud.data;
  if (n * step > data.byteLength || (cloud.height > 1 && cloud.row_step * cloud.height > data.byteLength)) {
    return { count: 0, positions: new Float32Array(0), colors: null, error: `the cloud's data is ${data.byteLength} bytes, less than ${cloud.width}x${cloud.height} points of ${step} bytes` };
  }
  const view = new DataView(data.buffer, data.byteOffset, data.byteLength);
  const little = !cloud.is_bigendian;
  const reader = (f) => {
    const r = READERS[f.datatype];
    if (!r) return null;
    return { get: r[0], offset: f.offset };
  };
  const rx = reader(fx); const ry = reader(fy); const rz = reader(fz);
  if (!rx || !ry || !rz) return { count: 0, positions: new Float32Array(0), colors: null, error: 'an x, y or z field has an unknown datatype' };
  const rgb = field(cloud, 'rgb') || field(cloud, 'rgba');
  const intensity = field(cloud, 'intensity') || field(cloud, 'i');
  if (mode === 'RGB8' && !rgb) mode = intensity ? 'Intensity' : 'AxisColor';
  if (mode === 'Intensity' && !intensity) mode = 'AxisColor';
  const ri = intensity ? reader(intensity) : null;
  const positions = new Float32Array(n * 3);
  const colors = new Float32Array(n * 3);
  const values = mode === 'Intensity' || mode === 'AxisColor' ? new Float32Array(n) : null;
  let count = 0;
  const rowStep = cloud.row_step || cloud.width * step;
  for (let row = 0; row < cloud.height; row++) {
    for (let col = 0; col < cloud.width; col++) {
      const base = row * rowStep + col * step;
      const x = view[rx.get](base + rx.offset, little);
      const y = view[ry.get](base + ry.offset, little);
      const z = view[rz.get](base + rz.offset, little);
      if (Number.isNaN(x) || Number.isNaN(y) || Number.isNaN(z)) continue;
      const o = count * 3;
      positions[o] = x; positions[o + 1] = y; positions[o + 2] = z;
      if (mode === 'RGB8') {
        colors[o] = view.getUint8(base + rgb.offset + (little ? 2 : 1)) / 255;
        colors[o + 1] = view.getUint8(base + rgb.offset + (little ? 1 : 2)) / 255;
        colors[o + 2] = view.getUint8(base + rgb.offset + (little ? 0 : 3)) / 255;
      } else if (mode === 'Intensity') {
        values[count] = view[ri.get](base + ri.offset, little);
      } else if (mode === 'AxisColor') {
        values[count] = axis === 0 ? x : axis === 1 ? y : z;
      } else {
        colors[o] = flat[0]; colors[o + 1] = flat[1]; colors[o + 2] = flat[2];
      }
      count++;
    }
  }
  if (values) colorByValue(values, count, colors);
  return { count, positions, colors, mode, error: null };
}

/** Colour points by a value, from its minimum (blue) to its maximum (red). */
export function colorByValue(values, count, colors) {
  let min = Infinity; let max = -Infinity;
  for (let i = 0; i < count; i++) { const v = values[i]; if (v < min) min = v; if (v > max) max = v; }
  const span = max > min ? max - min : 1;
  for (let i = 0; i < count; i++) rainbow((values[i] - min) / span, colors, i * 3);
}

/**
 * A LaserScan's points in its frame: {count, positions, colors|null}; ranges
 * outside [range_min, range_max] are left out, as rviz leaves them out.
 */
export function decodeScan(scan, { byIntensity = true } = {}) {
  const ranges = scan.ranges;
  const n = ranges.length;
  const positions = new Float32Array(n * 3);
  const hasIntensity = byIntensity && scan.intensities && scan.intensities.length === n;
  const values = hasIntensity ? new Float32Array(n) : null;
  let count = 0;
  for (let i = 0; i < n; i++) {
    const r = ranges[i];
    if (!(r >= scan.range_min && r <= scan.range_max)) continue;
    const a = scan.angle_min + i * scan.angle_increment;
    positions[count * 3] = r * Math.cos(a);
    positions[count * 3 + 1] = r * Math.sin(a);
    if (values) values[count] = scan.intensities[i];
    count++;
  }
  let colors = null;
  if (values) { colors = new Float32Array(n * 3); colorByValue(values, count, colors); }
  return { count, positions, colors };
}
