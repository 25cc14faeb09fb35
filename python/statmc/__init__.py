"""statmc from Python: statistical Monte Carlo denoising (docs/python.md).

Images are dicts of named layers, each an H x W x C float32 numpy array: the beauty under
"beauty" (R,G,B, with A when present), every other layer under its own name ("variance",
"sampleCount", "albedo", "bounce1.variance", ...). The operators are the statmc tool's
plugins, with the same parameters, defaults and error messages as the command line:

    import statmc
    out = statmc.denoise("frame.exr", radius=8)
    statmc.write_statistics("frame-denoised.exr", out)
"""

import os
import sys

from ._build import PYTHON_EXECUTABLE, PYTHON_VERSION, VERSION

__version__ = VERSION

try:
    import numpy as np
except ImportError as e:
    raise ImportError(
        f"statmc needs numpy, which this Python ({sys.executable}) does not have: "
        "pip install numpy, or make the venv with --system-site-packages to use Debian's "
        "python3-numpy") from e

try:
    from ._statmc import FileError, ToolError  # noqa: F401  (part of the API)
    from . import _statmc
except ImportError as e:
    _running = f"{sys.version_info.major}.{sys.version_info.minor}"
    if _running == PYTHON_VERSION:
        raise
    raise ImportError(
        f"statmc's native module was built for Python {PYTHON_VERSION} ({PYTHON_EXECUTABLE}); "
        f"this is Python {_running} ({sys.executable}). Import it from that interpreter, or "
        "build statmc for this one with cmake -DPython3_EXECUTABLE=" + sys.executable +
        f" ({e})") from e

__all__ = ["__version__", "Image", "read_statistics", "write_statistics", "denoise", "passes", "merge",
           "compare", "verify", "oidn", "FileError", "ToolError"]

BEAUTY = "beauty"
# The order of a layer's channels: colour, then vector, then whatever else in file order.
_SUFFIX_ORDER = ["R", "G", "B", "A", "X", "Y", "Z"]


class Image(dict):
    """Named layers (H x W x C float32 arrays) with the channel suffixes of each layer,
    the header attributes (int, float and str ones) and the data window's origin."""

    def __init__(self, layers=(), channels=None, attributes=None, origin=(0, 0)):
        super().__init__(layers)
        self.channels = dict(channels or {})
        self.attributes = dict(attributes or {})
        self.origin = tuple(origin)
        self.report = ""
        # (names, pixels, layers, channels) of the array this image's layers are views of,
        # as statmc returned it: passed back whole while no layer was replaced.
        self._source = None

    def channel_names(self):
        """The file's channel names, layer by layer."""
        names = []
        for layer in self:
            for suffix in self._suffixes(layer):
                names.append(_channel_name(layer, suffix))
        return names

    def _suffixes(self, layer):
        array = self[layer]
        if array.ndim != 3:
            raise ValueError(f"layer {layer}: expected an H x W x C array, got shape "
                             f"{array.shape}")
        suffixes = self.channels.get(layer) or _default_suffixes(layer, array.shape[2])
        if len(suffixes) != array.shape[2]:
            raise ValueError(f"layer {layer}: {array.shape[2]} channels but suffixes "
                             f"{suffixes}")
        return suffixes

    def _pixels(self):
        """One H x W x N float32 array of every channel, in channel_names() order."""
        shapes = {self[layer].shape[:2] for layer in self}
        if len(shapes) != 1:
            raise ValueError(f"the layers differ in size: {sorted(shapes)}")
        for layer in self:
            self._suffixes(layer)
        arrays = [np.asarray(self[layer], dtype=np.float32) for layer in self]
        return np.ascontiguousarray(np.concatenate(arrays, axis=2), dtype=np.float32)

    def _native(self):
        source = self._source
        if (source is not None and self.keys() == source[2].keys()
                and all(self[layer] is view for layer, view in source[2].items())
                and self.channels == source[3]):
            return (source[0], source[1], self.attributes, self.origin)
        return (self.channel_names(), self._pixels(), self.attributes, self.origin)


def _channel_name(layer, suffix):
    if layer == BEAUTY:
        return suffix
    return f"{layer}.{suffix}" if suffix else layer


def _default_suffixes(layer, count):
    if count == 3:
        return ["X", "Y", "Z"] if layer in ("normal", "position") else ["R", "G", "B"]
    if count == 4:
        return ["R", "G", "B", "A"]
    if count == 1:
        return ["Z"] if layer == "depth" else ["Y"]
    raise ValueError(f"layer {layer}: give the suffixes of its {count} channels in "
                     f"Image.channels['{layer}']")


def _channels_of(pixels, indices):
    """(pixels[:, :, indices], whether it is a view): a view where the indices run in steps
    of one, either way (a layer's channels side by side in the file, R,G,B or B,G,R), else
    a copy."""
    first, last = indices[0], indices[-1]
    step = 1 if last >= first else -1
    if indices == list(range(first, last + step, step)):
        stop = last + step if last + step >= 0 else None
        return pixels[:, :, first:stop:step], True
    return pixels[:, :, indices], False


def _from_native(native):
    names, pixels, attributes, origin = native
    groups = {}
    for index, name in enumerate(names):
        layer, _, suffix = name.rpartition(".")
        if not layer:
            layer = BEAUTY if name in _SUFFIX_ORDER[:4] else name
            suffix = name if layer == BEAUTY else ""
        groups.setdefault(layer, []).append((suffix, index))
    image = Image(attributes=attributes, origin=origin)
    all_views = True
    for layer, members in groups.items():
        members.sort(key=lambda m: _SUFFIX_ORDER.index(m[0]) if m[0] in _SUFFIX_ORDER
                     else len(_SUFFIX_ORDER))
        image[layer], is_view = _channels_of(pixels, [index for _, index in members])
        all_views = all_views and is_view
        image.channels[layer] = [suffix for suffix, _ in members]
    if all_views:  # a copied layer's edits would not be in `pixels`
        image._source = (names, pixels, dict(image),
                         {k: list(v) for k, v in image.channels.items()})
    return image


def _image(source, origin=(0, 0)):
    if isinstance(source, Image):
        return source
    if isinstance(source, (str, os.PathLike)):
        return read_statistics(source)
    if isinstance(source, np.ndarray) and source.ndim == 3 and source.shape[2] == 3:
        # An H x W x 3 array: a beauty (another denoiser's output, for verify).
        return Image({BEAUTY: source}, origin=origin)
    raise TypeError(f"expected a path, a statmc.Image or an H x W x 3 array, got "
                    f"{type(source).__name__}")


def _run(operator, sources, options, nthreads, previous=(), next=()):
    inputs = [_image(s)._native() for s in sources]
    frames = {"previous": [_image(s)._native() for s in previous],
              "next": [_image(s)._native() for s in next]}
    labels = [os.fspath(s) if isinstance(s, (str, os.PathLike)) else f"image {k}"
              for k, s in enumerate(sources)]
    # from_= for from=: Python's reserved words take a trailing underscore.
    options = {(name[:-1] if name.endswith("_") else name): value
               for name, value in options.items()}
    native, report = _statmc.run(operator, inputs, labels, options, nthreads=nthreads, **frames)
    result = _from_native(native)
    result.report = report
    return result


def read_statistics(path):
    """The layers of subimage 0 of an image file (statmc's own checks apply)."""
    return _from_native(_statmc.read(os.fspath(path)))


def write_statistics(path, image):
    """Writes an Image as OpenEXR under the layer contract's storage rules (float,
    lossless), through a temporary file: a failed write leaves nothing behind."""
    if not isinstance(image, Image):
        raise TypeError(f"expected a statmc.Image, got {type(image).__name__}")
    names, pixels, attributes, origin = image._native()
    _statmc.write(os.fspath(path), names, pixels, attributes, origin)


def denoise(source, nthreads=0, previous=(), next=(), **options):
    """The denoise operator (statmc --help denoise) on a path or an Image. For temporal=K,
    `previous` and `next` are the frames around it, nearest first (paths or Images)."""
    return _run("denoise", [source], options, nthreads, previous, next)


def passes(sources, nthreads=0, **options):
    """K plain renders of one frame (paths or Images) -> their statistics."""
    return _run("passes", list(sources), options, nthreads)


def merge(sources, nthreads=0, **options):
    """Statistics images of one frame (farm tasks) merged exactly."""
    return _run("merge", list(sources), options, nthreads)


def verify(source, candidate, nthreads=0, **options):
    """The verify operator (statmc --help verify): `candidate`, another denoiser's output of
    the frame `source` (a path, an Image, or an H x W x 3 array over its data window), kept
    where the pixels' own statistics cannot reject it and statmc's estimate where they and
    that estimate both can (docs/method.md §15);
    the map of rejections is the result's "diagnostics" layer (1: the pixel's test, 2: its
    box's, 3: both)."""
    source = _image(source)
    return _run("verify", [source, _image(candidate, source.origin)], options, nthreads)


def oidn(source, nthreads=0, **options):
    """The oidn operator (statmc --help oidn): Intel Open Image Denoise on the beauty, from
    the library of the pyoidn wheel when it is importable and STATMC_OIDN_LIBRARY is unset.
    Its output is a candidate for verify()."""
    if not os.environ.get("STATMC_OIDN_LIBRARY") and "library" not in options:
        library = _pyoidn_library()
        if library:
            options["library"] = library
    return _run("oidn", [source], options, nthreads)


def _pyoidn_library():
    """The OIDN library inside the pyoidn package, or None where pyoidn is absent."""
    import importlib.util
    spec = importlib.util.find_spec("pyoidn")
    if spec is None or not spec.submodule_search_locations:
        return None
    for location in spec.submodule_search_locations:
        path = os.path.join(location, "oidn", "lib", "libOpenImageDenoise.so.2")
        if os.path.exists(path):
            return path
    return None


METRICS = ("RMSE", "MAE", "relMSE", "SSIM", "DSSIM")


def compare(image, reference, nthreads=0, **options):
    """The compare operator: the absolute error image, with the metrics as numbers in its
    .metrics dict (RMSE, MAE, relMSE, SSIM, DSSIM) and as the table in its .report."""
    result = _run("compare", [image, reference], options, nthreads)
    result.metrics = {name: result.attributes[f"statmc:compare:{name}"] for name in METRICS}
    return result


# Each operator's docstring ends with its parameter table, as `statmc --help OP` prints it.
for _function, _operator in ((denoise, "denoise"), (passes, "passes"), (merge, "merge"),
                             (compare, "compare"), (verify, "verify"), (oidn, "oidn")):
    if _function.__doc__ is not None:  # None under python -OO
        _function.__doc__ += "\n\n" + _statmc.help(_operator)
