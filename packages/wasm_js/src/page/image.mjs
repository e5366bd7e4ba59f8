// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * sensor_msgs/Image and sensor_msgs/CompressedImage for display: pixels as
 * RGBA (ImageData layout), and compressed images as a Blob the browser
 * decodes (createImageBitmap).
 */

export const IMAGE_TYPES = new Set(['sensor_msgs/msg/Image']);
export const COMPRESSED_IMAGE_TYPES = new Set(['sensor_msgs/msg/CompressedImage']);

/** An image the view cannot show; says what it is and what is supported. */
export class ImageError extends Error {}

const CHANNELS = {
  rgb8: 3, bgr8: 3, rgba8: 4, bgra8: 4, mono8: 1, '8UC1': 1, '8UC3': 3, '8UC4': 4,
  mono16: 2, '16UC1': 2, '32FC1': 4,
};

/**
 * Convert a decoded sensor_msgs/Image to RGBA pixels.
 *
 * @returns {{width:number, height:number, rgba:Uint8ClampedArray}}
 */
export function imageToRgba(msg) {
  const { width, height, encoding, step } = msg;
  const data = msg.data;
  const bytesPerPixel = CHANNELS[encoding];
  if (bytesPerPixel === undefined) {
    throw new ImageError(`image encoding '${encoding}' is not shown (shown: ${Object.keys(CHANNELS).join(', ')})`);
  }
  if (step < width * bytesPerPixel || data.length < step * height) {
    throw new ImageError(`a ${width}x${height} ${encoding} image needs ${width * bytesPerPixel * height} bytes, the message has ${data.length} (step ${step})`);
  }
  const rgba = new Uint8ClampedArray(width * height * 4);
  const bigEndian = Boolean(msg.is_bigendian);
  let floatView = null;
  let lo = 0;
  let hi = 1;
  if (encoding === '32FC1') {
    floatView = new DataView(data.buffer, data.byteOffset, data.byteLength);
    lo = Infinity;
    hi = -Infinity;
    for (let y = 0; y < height; y++) {
      for (let x = 0; x < width; x++) {
        const f = floatView.getFloat32(y * step + x * 4, !bigEndian);
        if (Number.isFinite(f)) { if (f < lo) lo = f; if (f > hi) hi = f; }
      }
    }
    if (!(hi > lo)) { lo = 0; hi = 1; }
  }
  for (let y = 0; y < height; y++) {
    let src = y * step;
    let dst = y * width * 4;
    for (let x = 0; x < width; x++, dst += 4) {
      switch (encoding) {
        case 'rgb8': case '8UC3':
          rgba[dst] = data[src]; rgba[dst + 1] = data[src + 1]; rgba[dst + 2] = data[src + 2]; rgba[dst + 3] = 255; src += 3; break;
        case 'bgr8':
          rgba[dst] = data[src + 2]; rgba[dst + 1] = data[src + 1]; rgba[dst + 2] = data[src]; rgba[dst + 3] = 255; src += 3; break;
        case 'rgba8': case '8UC4':
          rgba[dst] = data[src]; rgba[dst + 1] = data[src + 1]; rgba[dst + 2] = data[src + 2]; rgba[dst + 3] = data[src + 3]; src += 4; break;
        case 'bgra8':
          rgba[dst] = data[src + 2]; rgba[dst + 1] = data[src + 1]; rgba[dst + 2] = data[src]; rgba[dst + 3] = data[src + 3]; src += 4; break;
        case 'mono8': case '8UC1':
          rgba[dst] = rgba[dst + 1] = rgba[dst + 2] = data[src]; rgba[dst + 3] = 255; src += 1; break;
        case 'mono16': case '16UC1': {
          const v = bigEndian ? (data[src] << 8) | data[src + 1] : (data[src + 1] << 8) | data[src];
          rgba[dst] = rgba[dst + 1] = rgba[dst + 2] = v >> 8; rgba[dst + 3] = 255; src += 2; break;
        }
        default: { // 32FC1, scaled to the image's range
          const f = floatView.getFloat32(src, !bigEndian);
          const g = Number.isFinite(f) ? Math.round(255 * (f - lo) / (hi - lo)) : 0;
          rgba[dst] = rgba[dst + 1] = rgba[dst + 2] = g; rgba[dst + 3] = 255; src += 4;
        }
      }
    }
  }
  return { width, height, rgba };
}

/** The MIME type of a sensor_msgs/CompressedImage format ('jpeg', 'png; ...'). */
export function compressedMimeType(format) {
  const f = String(format || '').toLowerCase();
  if (f.includes('png')) return 'image/png';
  if (f.includes('jpeg') || f.includes('jpg')) return 'image/jpeg';
  if (f.includes('webp')) return 'image/webp';
  throw new ImageError(`compressed image format '${format}' is not shown (shown: jpeg, png, webp)`);
}

/**
 * Whether messages of a type are images: 'raw' for sensor_msgs/Image (or a
 * message with its fields: height, width, encoding, step, data as uint8[]),
 * 'compressed' for sensor_msgs/CompressedImage (or format + data), else null.
 */
export function imageKind(registry, type) {
  if (IMAGE_TYPES.has(type)) return 'raw';
  if (COMPRESSED_IMAGE_TYPES.has(type)) return 'compressed';
  if (!registry || !type || !registry.has(type)) return null;
  const fields = new Map(registry.message(type).fields.map((f) => [f.name, f]));
  const bytes = (f) => f && f.sequence && (f.type === 'uint8' || f.type === 'byte');
  const is = (name, t) => fields.has(name) && fields.get(name).type === t && !fields.get(name).sequence;
  if (bytes(fields.get('data')) && is('height', 'uint32') && is('width', 'uint32') && is('encoding', 'string') && is('step', 'uint32')) return 'raw';
  if (bytes(fields.get('data')) && is('format', 'string')) return 'compressed';
  return null;
}
