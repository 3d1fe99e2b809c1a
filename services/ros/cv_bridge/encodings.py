"""sensor_msgs' image encodings, as cv_bridge reads them: each one's numpy type, channels, colour
family and bit depth, and the steps that turn one encoding into another.

Named encodings carry colour (``rgb8``, ``bgr8``, ``mono16``, ``bayer_rggb8``, ``yuv422``...);
OpenCV's type names (``8UC3``, ``32FC1``...) carry none. Between two colour encodings the steps
are OpenCV colour conversions (``cv2.COLOR_*``, named here) and a change of bit depth, 8 <-> 16
bits scaled as cv_bridge scales them; without colour only the depth may change, and only for the
same number of channels. Pure tables: OpenCV itself is only loaded by :mod:`.core`.
"""

from __future__ import annotations

from typing import NamedTuple

from services.ros.cv_bridge.errors import CvBridgeError

__all__ = ["DEPTH", "Encoding", "cv_type_name", "encoding", "steps"]


class Encoding(NamedTuple):
    """One encoding: numpy ``dtype`` name, ``channels``, colour ``family`` (None: no colour)."""

    dtype: str
    channels: int
    family: str | None

    @property
    def depth(self) -> int:
        """Bits per channel value."""
        return {"uint8": 8, "int8": 8, "uint16": 16, "int16": 16, "int32": 32, "float32": 32, "float64": 64}[self.dtype]


# OpenCV's depth names and numpy's types, both ways.
_DEPTHS = {"8U": "uint8", "8S": "int8", "16U": "uint16", "16S": "int16", "32S": "int32", "32F": "float32", "64F": "float64"}
_DEPTH_OF = {dtype: name for name, dtype in _DEPTHS.items()}

_NAMED = {
    "mono8": Encoding("uint8", 1, "GRAY"),
    "mono16": Encoding("uint16", 1, "GRAY"),
    "rgb8": Encoding("uint8", 3, "RGB"),
    "bgr8": Encoding("uint8", 3, "BGR"),
    "rgba8": Encoding("uint8", 4, "RGBA"),
    "bgra8": Encoding("uint8", 4, "BGRA"),
    "rgb16": Encoding("uint16", 3, "RGB"),
    "bgr16": Encoding("uint16", 3, "BGR"),
    "rgba16": Encoding("uint16", 4, "RGBA"),
    "bgra16": Encoding("uint16", 4, "BGRA"),
    "yuv422": Encoding("uint8", 2, "YUV422"),  # UYVY
    "yuv422_yuy2": Encoding("uint8", 2, "YUV422_YUY2"),
    **{
        f"bayer_{pattern}{bits}": Encoding("uint8" if bits == 8 else "uint16", 1, f"BAYER_{pattern.upper()}")
        for pattern in ("rggb", "bggr", "gbrg", "grbg")
        for bits in (8, 16)
    },
}

_COLOURS = ("GRAY", "RGB", "BGR", "RGBA", "BGRA")
# (from, to) -> OpenCV's colour conversion code, by name.
_CODES: dict[tuple[str, str], str] = {
    (a, b): f"COLOR_{a}2{b}" for a in _COLOURS for b in _COLOURS if a != b and not (a == "GRAY" and b == "GRAY")
}
for _yuv, _suffix in (("YUV422", "UYVY"), ("YUV422_YUY2", "YUY2")):
    for _to in _COLOURS:
        _CODES[(_yuv, _to)] = f"COLOR_YUV2{_to}_{_suffix}"
# OpenCV names a Bayer pattern by its second row's first two pixels: ROS's RGGB is its BayerBG.
for _pattern, _opencv in (("RGGB", "BG"), ("BGGR", "RG"), ("GBRG", "GR"), ("GRBG", "GB")):
    for _to in ("GRAY", "RGB", "BGR"):
        _CODES[(f"BAYER_{_pattern}", _to)] = f"COLOR_Bayer{_opencv}2{_to}"

DEPTH = "depth"
"""The step that changes the bit depth (values scaled between 8 and 16 bits)."""


def encoding(name: str) -> Encoding:
    """The encoding called ``name``, or CvBridgeError as cv_bridge says it."""
    if not isinstance(name, str):
        raise CvBridgeError(f"an image encoding is a string such as 'bgr8', got {name!r}")
    known = _NAMED.get(name)
    if known is not None:
        return known
    depth, c, channels = name.partition("C")
    if c and depth in _DEPTHS and channels in ("1", "2", "3", "4"):
        return Encoding(_DEPTHS[depth], int(channels), None)
    raise CvBridgeError(f"Unrecognized image encoding [{name}]")


def cv_type_name(dtype: str, channels: int) -> str:
    """OpenCV's type name for numpy ``dtype`` and ``channels`` (``8UC3``)."""
    depth = _DEPTH_OF.get(dtype)
    if depth is None:
        raise CvBridgeError(
            f"numpy type {dtype} has no OpenCV type (it takes {', '.join(_DEPTH_OF)}): convert the image first, "
            "e.g. image.astype(numpy.uint8)"
        )
    return f"{depth}C{channels}"


def steps(source: str, destination: str) -> list[str]:
    """What turns ``source`` into ``destination``: colour codes (``COLOR_RGB2BGR``) and DEPTH."""
    src, dst = encoding(source), encoding(destination)
    if src.family is None:
        if dst.family is not None:
            raise CvBridgeError(f"[{source}] is not a color format. but [{destination}] is. The conversion does not make sense")
        if src.channels != dst.channels:
            raise CvBridgeError(f"[{source}] and [{destination}] do not have the same number of channel")
        return [DEPTH]
    if dst.family is None:
        if src.channels != dst.channels:
            raise CvBridgeError(
                f"[{source}] is a color format but [{destination}] is not so they must have the same OpenCV type, "
                "CV_8UC3, CV16UC1 ...."
            )
        return [DEPTH]
    if src.family == dst.family:
        return [DEPTH]
    code = _CODES.get((src.family, dst.family))
    if code is None:
        raise CvBridgeError(f"Unsupported conversion from [{source}] to [{destination}]")
    return [code, DEPTH] if src.depth != dst.depth else [code]
