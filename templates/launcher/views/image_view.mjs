// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// Shows the newest sensor_msgs/Image or CompressedImage of a topic.

import { compressedMimeType, imageToRgba } from '../../wasm_js/page/image.mjs';
import { h } from '../dom.mjs';

export class ImageView {
  constructor(compressed) {
    this.compressed = compressed;
    this.canvas = h('canvas.image', { width: 320, height: 240 });
    this.info = h('div.note');
    this.error = h('div.error-text');
    this.busy = false;
    this.element = h('div.image-view', {}, this.canvas, this.info, this.error);
  }

  /** Show the newest decoded message (older ones of a batch are skipped). */
  async show(msg) {
    if (this.busy) return;
    this.busy = true;
    try {
      this.error.textContent = '';
      const ctx = this.canvas.getContext('2d');
      if (this.compressed) {
        const blob = new Blob([msg.data], { type: compressedMimeType(msg.format) });
        const bitmap = await createImageBitmap(blob);
        this.resize(bitmap.width, bitmap.height);
        ctx.drawImage(bitmap, 0, 0);
        this.info.textContent = `${bitmap.width}×${bitmap.height} ${msg.format}, ${msg.data.length} bytes`;
        bitmap.close();
      } else {
        const { width, height, rgba } = imageToRgba(msg);
        this.resize(width, height);
        ctx.putImageData(new ImageData(rgba, width, height), 0, 0);
        this.info.textContent = `${width}×${height} ${msg.encoding}`;
      }
    } catch (e) {
      this.error.textContent = e.message;
    } finally {
      this.busy = false;
    }
  }

  resize(width, height) {
    if (this.canvas.width !== width || this.canvas.height !== height) {
      this.canvas.width = width;
      this.canvas.height = height;
      // small images are shown enlarged (pixelated), large ones fit the card
      this.canvas.style.width = `${Math.min(960, Math.max(320, width))}px`;
    }
  }
}
