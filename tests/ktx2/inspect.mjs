// Reads KTX 2.0 files with ktx-parse (a reader iblab did not write) and prints what the
// export tests check, as JSON: the header, each level's byte length, the DFD's samples, and
// level 0's texels as RGBA floats per face (decoded here from the file's vkFormat).
// Usage: node inspect.mjs FILE.ktx2 [--texels]
import { readFileSync } from 'node:fs';
import { read } from 'ktx-parse';

const VK_FORMAT_R16G16B16A16_SFLOAT = 97;
const VK_FORMAT_R32G32B32A32_SFLOAT = 109;

function halfToFloat(h) {
  const sign = h & 0x8000 ? -1 : 1;
  const exponent = (h >> 10) & 0x1f;
  const mantissa = h & 0x3ff;
  if (exponent === 0) return sign * mantissa * 2 ** -24;
  if (exponent === 31) return mantissa ? NaN : sign * Infinity;
  return sign * (1 + mantissa / 1024) * 2 ** (exponent - 15);
}

const [path, ...flags] = process.argv.slice(2);
const container = read(new Uint8Array(readFileSync(path)));
const out = {
  vkFormat: container.vkFormat,
  typeSize: container.typeSize,
  pixelWidth: container.pixelWidth,
  pixelHeight: container.pixelHeight,
  pixelDepth: container.pixelDepth,
  layerCount: container.layerCount,
  faceCount: container.faceCount,
  supercompressionScheme: container.supercompressionScheme,
  levels: container.levels.map((l) => ({ byteLength: l.levelData.byteLength, uncompressedByteLength: l.uncompressedByteLength })),
  dfd: container.dataFormatDescriptor.map((d) => ({
    colorModel: d.colorModel,
    transferFunction: d.transferFunction,
    samples: d.samples.map((s) => ({ bitOffset: s.bitOffset, bitLength: s.bitLength, channelType: s.channelType })),
  })),
  keyValue: Object.fromEntries(Object.entries(container.keyValue).map(([k, v]) => [k, typeof v === 'string' ? v : Array.from(v).length])),
};
if (flags.includes('--texels')) {
  const level = container.levels[0].levelData;
  const view = new DataView(level.buffer, level.byteOffset, level.byteLength);
  const half = container.vkFormat === VK_FORMAT_R16G16B16A16_SFLOAT;
  if (!half && container.vkFormat !== VK_FORMAT_R32G32B32A32_SFLOAT) throw new Error(`${path}: vkFormat ${container.vkFormat} is not RGBA16F/RGBA32F`);
  const texels = level.byteLength / (half ? 8 : 16);
  const perFace = texels / container.faceCount;
  out.level0 = [];
  for (let f = 0; f < container.faceCount; ++f) {
    const face = [];
    for (let i = 0; i < perFace * 4; ++i) {
      const k = f * perFace * 4 + i;
      face.push(half ? halfToFloat(view.getUint16(2 * k, true)) : view.getFloat32(4 * k, true));
    }
    out.level0.push(face);
  }
}
process.stdout.write(JSON.stringify(out));
