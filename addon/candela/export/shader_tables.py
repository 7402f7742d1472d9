"""The shader-program part of the schema (docs/architecture.md, "Shader programs"): images, ColorRamp tables,
constants, operations, program ranges and input bindings, shared by every material and the world of one export.

A `Program` is one material's (or the world's) flat operation list. Operation k writes register k and reads only
registers before it; values are either Python constants (3-tuples, folded here) or `Reg`s. Images are read once per
export with `foreach_get` (no per-pixel Python) and kept as Blender stores them: 8-bit images go to the byte pool
(4 bytes a texel) with their encoded values, which the renderer decodes after filtering for sRGB images, as Cycles
does; float images go to the float pool, already scene-linear.
"""

import numpy as np

from .. import schema


def image_key(image):
    """What a loaded image's texels depend on: which image (its data block), its size, source and colour space
    setting. Edits of its pixels (painting, reloading) arrive as depsgraph updates of the image, which drop its
    entries (viewport/scene_sync.py)."""
    return (image.name, image.as_pointer(), tuple(image.size), image.source, image.colorspace_settings.name,
            image.filepath_raw)


class Reg:
    """A register of the program being built (its index within the program)."""
    __slots__ = ("index",)

    def __init__(self, index):
        self.index = index

    def __repr__(self):
        return f"Reg({self.index})"


def is_const(value):
    return not isinstance(value, Reg)


def const3(value):
    """A float or a sequence as an RGB / XYZ 3-tuple of floats (a float is broadcast)."""
    if isinstance(value, (int, float)):
        return (float(value),) * 3
    v = tuple(float(c) for c in value)
    return v[:3] if len(v) >= 3 else (v + (0.0,) * 3)[:3]


MISSING_COLOR = (1.0, 0.0, 1.0)   # what Cycles shows for an image it cannot load


class Program:
    """The operations of one program; registers are indices into `ops`."""

    def __init__(self, tables):
        self.tables = tables
        self.ops = []            # [code, a, b, c, i0, i1, i2, i3]
        self._consts = {}        # 3-tuple → Reg

    def op(self, name, a=None, b=None, c=None, i=(0, 0, 0, 0)):
        regs = [self.reg(x).index if x is not None else 0 for x in (a, b, c)]
        imm = list(i) + [0] * (4 - len(i))
        self.ops.append([self.tables.enum("shader_ops")[name], *regs, *(int(x) for x in imm)])
        return Reg(len(self.ops) - 1)

    def reg(self, value):
        """`value` as a register: constants become CONST operations (one per distinct value)."""
        if isinstance(value, Reg):
            return value
        value = const3(value)
        reg = self._consts.get(value)
        if reg is None:
            offset = self.tables.add_consts(value)
            reg = self._consts[value] = self.op("CONST", i=(offset,))
        return reg

    # ---- arithmetic with constant folding (per channel, as the native MATH operation) --------------------------

    def math(self, name, a, b=0.0, clamp=False):
        if is_const(a) and is_const(b) and name in _FOLD:
            out = tuple(_FOLD[name](x, y) for x, y in zip(const3(a), const3(b)))
            return tuple(min(max(v, 0.0), 1.0) for v in out) if clamp else out
        return self.op("MATH", a, b, 0.0, i=(self.tables.enum("math_ops")[name], int(clamp)))

    def mul(self, a, b):
        if is_const(a) and all(v == 1.0 for v in const3(a)):
            return b
        if is_const(b) and all(v == 1.0 for v in const3(b)):
            return a
        return self.math("MULTIPLY", a, b)

    def add(self, a, b):
        if is_const(a) and all(v == 0.0 for v in const3(a)):
            return b
        if is_const(b) and all(v == 0.0 for v in const3(b)):
            return a
        return self.math("ADD", a, b)

    def one_minus(self, a):
        return self.math("SUBTRACT", 1.0, a)

    def clamp01(self, a):
        return self.math("MULTIPLY", a, 1.0, clamp=True)


_FOLD = {
    "ADD": lambda x, y: x + y,
    "SUBTRACT": lambda x, y: x - y,
    "MULTIPLY": lambda x, y: x * y,
}


class ShaderTables:
    def __init__(self, warnings, image_cache=None):
        """`image_cache`: a dict kept across exports (the viewport's) from an image's key to its loaded texels,
        so images are read from Blender once, not on every export (ImageCache.key says when one must be read
        again)."""
        self.warnings = warnings
        self.image_cache = image_cache
        self._enums = {}
        self.texel_chunks = {"FLOAT": [], "BYTE": []}   # (N, 4) float32 / uint8 arrays per pool
        self.texel_count = {"FLOAT": 0, "BYTE": 0}
        self.texture_info = []       # [first texel, width, height, colour space, storage]
        self._images = {}            # image pointer → texture index, or None when it cannot be loaded
        self.ramps = []              # (256, 4) float32 arrays
        self.consts = []
        self.ops = []
        self.program_start = [0]
        self.bindings = []           # [target, row, column, channels, program, register]
        self.attribute_names = []    # slot → mesh attribute name (`corner_attributes`; RENDER_COLOR: the default)

    def enum(self, key):
        table = self._enums.get(key)
        if table is None:
            table = self._enums[key] = schema.shader_enum(key)
        return table

    def add_consts(self, values):
        offset = len(self.consts)
        self.consts.extend(float(v) for v in values)
        return offset

    def add_program(self, program):
        """Appends a finished program; returns its index (None for a program without operations)."""
        if not program.ops:
            return None
        self.ops.extend(program.ops)
        self.program_start.append(len(self.ops))
        return len(self.program_start) - 2

    def bind(self, target, row, column, channels, program, reg):
        self.bindings.append([self.enum("input_targets")[target], int(row), int(column), int(channels), int(program),
                              reg.index])

    # ---- images -------------------------------------------------------------------------------------------------

    def image(self, image, owner):
        """Texture index of a Blender image, or None (with one warning naming it and `owner`) if it has no pixels."""
        key = image.as_pointer()
        if key in self._images:
            index = self._images[key]
        else:
            index = self._images[key] = self._load_image(image)
        if index is None:
            where = f" ({image.filepath})" if image.filepath else ""
            self.warnings.add(f"Candela: {owner}: image '{image.name}'{where} cannot be loaded (missing file?); "
                              "rendering it magenta, as Cycles does")
        return index

    def _load_image(self, image):
        if self.image_cache is None:
            return self._add_texels(*self._read_image(image))
        key = image_key(image)
        entry = self.image_cache.get(key)
        if entry is None:
            entry = self.image_cache[key] = self._read_image(image)
        return self._add_texels(*entry)

    def _add_texels(self, texels, storage, width, height, color_space):
        if texels is None:
            return None
        self.texture_info.append([self.texel_count[storage], width, height, self.enum("tex_color_spaces")[color_space],
                                  self.enum("tex_storages")[storage]])
        self.texel_chunks[storage].append(texels)
        self.texel_count[storage] += width * height
        return len(self.texture_info) - 1

    def _read_image(self, image):
        """(texels, storage, width, height, colour space) of a Blender image; texels None if it has no pixels."""
        width, height = (int(v) for v in image.size)   # reading the size loads the image if it can
        if width <= 0 or height <= 0 or not image.has_data:
            return None, "FLOAT", 0, 0, "LINEAR"
        if image.source == 'TILED':
            self.warnings.add(f"Candela: image '{image.name}' is tiled (UDIM); only its first tile is used")
        channels = int(image.channels)
        buf = np.empty(width * height * channels, np.float32)
        image.pixels.foreach_get(buf)
        px = buf.reshape(height * width, channels)
        if channels == 4:
            rgba = px
        else:
            rgba = np.ones((height * width, 4), np.float32)
            if channels >= 3:
                rgba[:, :3] = px[:, :3]
            else:   # grey (+ alpha)
                rgba[:, :3] = px[:, :1]
                if channels == 2:
                    rgba[:, 3] = px[:, 1]
        # In place: a 4096² image is 67 M floats, and every temporary costs a second or more.
        if image.is_float:
            storage = "FLOAT"
            texels = np.nan_to_num(rgba, copy=False, nan=0.0, posinf=0.0, neginf=0.0)
        else:   # Blender hands 8-bit texels out as k/255: back to the bytes they are
            storage = "BYTE"
            np.multiply(rgba, 255.0, out=rgba)
            np.add(rgba, 0.5, out=rgba)
            np.clip(rgba, 0.0, 255.0, out=rgba)
            texels = rgba.astype(np.uint8)
        return texels, storage, width, height, self._color_space(image)

    def _color_space(self, image):
        """LINEAR or SRGB (decode after filtering). Float buffers are scene-linear already (Blender converts them
        on load); 8-bit buffers hold the file's encoded values."""
        if image.is_float:
            return "LINEAR"
        name = image.colorspace_settings.name
        if name in ("Non-Color", "Raw", "Linear", "Linear ACES", "Linear ACEScg"):
            if name.startswith("Linear "):
                self.warnings.add(f"Candela: image '{image.name}' uses the colour space '{name}'; its values are "
                                  "used as linear Rec.709")
            return "LINEAR"
        if name != "sRGB":
            self.warnings.add(f"Candela: image '{image.name}' uses the colour space '{name}', which Candela does "
                              "not convert; it is decoded as sRGB")
        return "SRGB"

    # ---- ColorRamp ----------------------------------------------------------------------------------------------

    def ramp(self, color_ramp):
        """Index of a ColorRamp baked into RAMP_SIZE entries at i/(RAMP_SIZE − 1), as Cycles bakes it."""
        n = schema.RAMP_SIZE
        table = np.array([tuple(color_ramp.evaluate(i / (n - 1))) for i in range(n)], np.float32).reshape(n, 4)
        self.ramps.append(table)
        return len(self.ramps) - 1

    def attribute_slot(self, name):
        """The `corner_attributes` slot of a mesh attribute name (shared by every material of the export)."""
        if name not in self.attribute_names:
            self.attribute_names.append(name)
        return self.attribute_names.index(name)

    def curve_table(self, rows):
        """Index of a table of RAMP_SIZE given (r, g, b) rows (RGB/Vector/Float Curves baked over their x range)."""
        table = np.ones((schema.RAMP_SIZE, 4), np.float32)
        table[:, :3] = np.asarray(rows, np.float32).reshape(schema.RAMP_SIZE, 3)
        self.ramps.append(table)
        return len(self.ramps) - 1

    # ---- arrays -------------------------------------------------------------------------------------------------

    def arrays(self):
        if not self.ops:
            return {}
        out = {
            "shader_consts": np.array(self.consts or [0.0], np.float32),
            "shader_ops": np.array(self.ops, np.uint32).reshape(-1, 8),
            "shader_programs": np.array(self.program_start, np.uint32),
        }
        if self.texture_info:
            for storage, key in (("FLOAT", "textures"), ("BYTE", "textures_u8")):
                chunks = self.texel_chunks[storage]
                if chunks:
                    out[key] = chunks[0] if len(chunks) == 1 else np.concatenate(chunks)
            out["texture_info"] = np.array(self.texture_info, np.uint32).reshape(-1, 5)
        if self.ramps:
            out["ramps"] = np.stack(self.ramps).astype(np.float32)
        if self.bindings:
            out["input_bindings"] = np.array(self.bindings, np.uint32).reshape(-1, 6)
        return out
