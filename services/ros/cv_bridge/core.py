"""``cv_bridge.CvBridge``: sensor_msgs images to OpenCV (numpy) images and back, over the real
OpenCV (``opencv-python-headless``, Skydeck's vision extra).

    bridge = CvBridge()
    frame = bridge.imgmsg_to_cv2(msg, desired_encoding='bgr8')        # a writable numpy array
    out = bridge.cv2_to_imgmsg(frame, encoding='bgr8', header=msg.header)
    jpeg = bridge.cv2_to_compressed_imgmsg(frame)                      # dst_format='jpg' | 'png'
    again = bridge.compressed_imgmsg_to_cv2(jpeg, 'rgb8')

Rows of a message are read with its ``step`` (padding after each row is skipped) and byte order
(``is_bigendian``); the array returned is always a copy in native byte order, so drawing on it
(``cv2.circle``) is safe. Conversions between encodings are cv_bridge's (:mod:`.encodings`).
"""

from __future__ import annotations

import sys
from typing import Any

import numpy as np

from services.ros.cv_bridge.encodings import DEPTH, Encoding, cv_type_name, steps
from services.ros.cv_bridge.encodings import encoding as _encoding
from services.ros.cv_bridge.errors import CvBridgeError
from shared_models.sensor_msgs import CompressedImage, Image
from shared_models.std_msgs import Header

__all__ = ["CvBridge", "getCvType"]

_PASSTHROUGH = "passthrough"


def _cv2() -> Any:
    import cv2  # the vision extra; `import cv_bridge` already said how to install it if missing

    return cv2


def getCvType(encoding_name: str) -> int:
    """OpenCV's type constant for an encoding (``getCvType('bgr8') == cv2.CV_8UC3``)."""
    found = _encoding(encoding_name)
    return int(getattr(_cv2(), f"CV_{cv_type_name(found.dtype, found.channels)}"))


class CvBridge:
    """Converts between sensor_msgs Image/CompressedImage messages and OpenCV images."""

    def __init__(self) -> None:
        _cv2()

    # -- encodings (cv_bridge's helper names) -------------------------------------------------

    def encoding_to_cvtype2(self, encoding_name: str) -> int:
        return getCvType(encoding_name)

    def encoding_to_dtype_with_channels(self, encoding_name: str) -> tuple[str, int]:
        found = _encoding(encoding_name)
        return found.dtype, found.channels

    def dtype_with_channels_to_cvtype2(self, dtype: Any, n_channels: int) -> str:
        return cv_type_name(np.dtype(dtype).name, n_channels)

    # -- sensor_msgs/Image --------------------------------------------------------------------

    def imgmsg_to_cv2(self, img_msg: Image, desired_encoding: str = _PASSTHROUGH) -> np.ndarray:
        """The image of ``img_msg`` as a numpy array (height x width, or height x width x
        channels), converted to ``desired_encoding`` ('bgr8', 'rgb8', 'mono8', ...) unless
        'passthrough'."""
        if not isinstance(img_msg, Image):
            raise CvBridgeError(f"imgmsg_to_cv2 takes a sensor_msgs Image, got {type(img_msg).__name__}")
        found = _encoding(img_msg.encoding)
        dtype = np.dtype(found.dtype).newbyteorder(">" if img_msg.is_bigendian else "<")
        height, width, channels = img_msg.height, img_msg.width, found.channels
        row = width * channels * dtype.itemsize
        if img_msg.step < row or len(img_msg.data) < img_msg.step * (height - 1) + row:
            raise CvBridgeError(
                f"the image's data does not fit its size: {width}x{height} {img_msg.encoding} needs rows of "
                f"{row} bytes, step is {img_msg.step}, data is {len(img_msg.data)} bytes"
            )
        view = np.ndarray(
            shape=(height, width, channels), dtype=dtype, buffer=img_msg.data,
            strides=(img_msg.step, channels * dtype.itemsize, dtype.itemsize),
        )  # fmt: skip
        image = np.array(view, dtype=dtype.newbyteorder("="), order="C")  # a writable copy, native order
        if channels == 1:
            image = image.reshape(height, width)
        if desired_encoding == _PASSTHROUGH:
            return image
        return self._convert(image, img_msg.encoding, desired_encoding)

    def cv2_to_imgmsg(self, cvim: Any, encoding: str = _PASSTHROUGH, header: Header | None = None) -> Image:
        """A sensor_msgs Image of ``cvim``; ``encoding`` names what its pixels are ('bgr8'...), and
        must fit its type ('passthrough': its OpenCV type, such as '8UC3')."""
        if not isinstance(cvim, np.ndarray | np.generic):
            raise TypeError("Your input type is not a numpy array")
        image = np.asarray(cvim)
        if image.ndim not in (2, 3):
            raise CvBridgeError(f"an image is 2-D (one channel) or 3-D (height x width x channels), got shape {image.shape}")
        cv_type = cv_type_name(image.dtype.name, 1 if image.ndim == 2 else image.shape[2])
        if encoding != _PASSTHROUGH:
            wanted = _encoding(encoding)
            if cv_type_name(wanted.dtype, wanted.channels) != cv_type:
                raise CvBridgeError(f"encoding specified as {encoding}, but image has incompatible type {cv_type}")
        data = np.ascontiguousarray(image).tobytes()
        big = image.dtype.byteorder == ">" or (image.dtype.byteorder == "=" and sys.byteorder == "big")
        return Image(
            header=header.model_copy(deep=True) if header is not None else Header(),
            height=image.shape[0],
            width=image.shape[1],
            encoding=cv_type if encoding == _PASSTHROUGH else encoding,
            is_bigendian=int(big and image.dtype.itemsize > 1),
            step=len(data) // image.shape[0] if image.shape[0] else 0,
            data=data,
        )

    # -- sensor_msgs/CompressedImage ----------------------------------------------------------

    def compressed_imgmsg_to_cv2(self, cmprs_img_msg: CompressedImage, desired_encoding: str = _PASSTHROUGH) -> np.ndarray:
        """The decoded image (BGR for colour, as OpenCV decodes), converted to ``desired_encoding``."""
        if not isinstance(cmprs_img_msg, CompressedImage):
            raise CvBridgeError(f"compressed_imgmsg_to_cv2 takes a sensor_msgs CompressedImage, got {type(cmprs_img_msg).__name__}")
        cv2 = _cv2()
        image = cv2.imdecode(np.frombuffer(cmprs_img_msg.data, dtype=np.uint8), cv2.IMREAD_UNCHANGED)
        if image is None:
            raise CvBridgeError(
                f"could not decode the compressed image ({len(cmprs_img_msg.data)} bytes, format {cmprs_img_msg.format!r})"
            )
        if desired_encoding == _PASSTHROUGH:
            return image  # type: ignore[no-any-return]
        return self._convert(image, _decoded_encoding(image), desired_encoding)

    def cv2_to_compressed_imgmsg(self, cvim: Any, dst_format: str = "jpg") -> CompressedImage:
        """A CompressedImage of ``cvim`` (BGR, as OpenCV encodes it) in ``dst_format`` ('jpg', 'png'...)."""
        if not isinstance(cvim, np.ndarray | np.generic):
            raise TypeError("Your input type is not a numpy array")
        cv2 = _cv2()
        try:
            ok, buffer = cv2.imencode(f".{dst_format}", np.asarray(cvim))
        except cv2.error as error:
            raise CvBridgeError(f"could not encode the image as {dst_format!r}: {str(error).strip()}") from None
        if not ok:
            raise CvBridgeError(f"could not encode the image as {dst_format!r}")
        return CompressedImage(format=dst_format, data=buffer.tobytes())

    # -- conversions --------------------------------------------------------------------------

    def _convert(self, image: np.ndarray, source: str, destination: str) -> np.ndarray:
        if source == destination:
            return image.copy()
        cv2 = _cv2()
        target = _encoding(destination)
        for step in steps(source, destination):
            if step == DEPTH:
                image = _change_depth(image, target)
            else:
                image = cv2.cvtColor(image, getattr(cv2, step))
        return image


def _change_depth(image: np.ndarray, target: Encoding) -> np.ndarray:
    """``image`` in ``target``'s numpy type, 8 <-> 16 bits scaled to the full range (as cv_bridge);
    integer results rounded and saturated (as OpenCV's convertTo)."""
    dtype = np.dtype(target.dtype)
    if image.dtype == dtype:
        return image.copy()
    source_bits, target_bits = image.dtype.itemsize * 8, dtype.itemsize * 8
    scale = 1.0
    if image.dtype.kind in "ui" and dtype.kind in "ui":
        if (source_bits, target_bits) == (8, 16):
            scale = 65535.0 / 255.0
        elif (source_bits, target_bits) == (16, 8):
            scale = 255.0 / 65535.0
    values = image.astype(np.float64) * scale
    if dtype.kind in "ui":
        limits = np.iinfo(dtype)
        values = np.clip(np.rint(values), limits.min, limits.max)
    return values.astype(dtype)


def _decoded_encoding(image: np.ndarray) -> str:
    """What ``cv2.imdecode`` gave: grey, BGR or BGRA, 8 or 16 bits."""
    bits = "16" if image.dtype == np.uint16 else "8"
    channels = 1 if image.ndim == 2 else image.shape[2]
    return {1: "mono", 3: "bgr", 4: "bgra"}.get(channels, "bgr") + bits
