"""cv_bridge over the real OpenCV: every kind of encoding there and back, cv_bridge's
conversions (channel order, grey, 8 <-> 16 bit scaling, Bayer, YUV), rows with padding and
big-endian data, compressed images, and cv_bridge's errors in its words."""

from __future__ import annotations

import numpy as np
import pytest

cv2 = pytest.importorskip("cv2", reason="the vision extra is not installed: make install-vision")

from services.ros.cv_bridge import CvBridge, CvBridgeError, getCvType  # noqa: E402
from services.ros.cv_bridge.encodings import _CODES  # noqa: E402
from shared_models.errors import SkydeckError  # noqa: E402
from shared_models.sensor_msgs import CompressedImage, Image  # noqa: E402
from shared_models.std_msgs import Header  # noqa: E402

pytestmark = pytest.mark.timeout(30)

bridge = CvBridge()
rng = np.random.default_rng(3)


def _image(shape: tuple[int, ...], dtype: str = "uint8") -> np.ndarray:
    if np.dtype(dtype).kind == "f":
        return rng.normal(size=shape).astype(dtype)
    info = np.iinfo(dtype)
    return rng.integers(info.min, info.max, size=shape, endpoint=True).astype(dtype)


@pytest.mark.parametrize(
    ("encoding", "shape", "dtype"),
    [
        ("bgr8", (4, 5, 3), "uint8"), ("rgb8", (4, 5, 3), "uint8"), ("mono8", (4, 5), "uint8"),
        ("mono16", (4, 5), "uint16"), ("bgra8", (4, 5, 4), "uint8"), ("rgba16", (3, 2, 4), "uint16"),
        ("32FC1", (4, 5), "float32"), ("64FC3", (2, 3, 3), "float64"), ("16SC2", (2, 3, 2), "int16"),
        ("passthrough", (4, 5, 3), "uint8"),
    ],
)  # fmt: skip
def test_there_and_back_for_each_kind_of_encoding(encoding: str, shape: tuple[int, ...], dtype: str) -> None:
    image = _image(shape, dtype)
    header = Header(frame_id="camera")
    msg = bridge.cv2_to_imgmsg(image, encoding=encoding, header=header)
    channels = 1 if len(shape) == 2 else shape[2]
    assert (msg.height, msg.width, msg.step) == (shape[0], shape[1], shape[1] * channels * np.dtype(dtype).itemsize)
    assert msg.header.frame_id == "camera" and msg.is_bigendian == 0
    if encoding == "passthrough":
        assert msg.encoding == "8UC3"
    back = bridge.imgmsg_to_cv2(Image.model_validate_json(msg.model_dump_json()))  # through JSON, as on the wire
    assert back.dtype == image.dtype and back.shape == image.shape and np.array_equal(back, image)
    back[0, 0] = 0  # writable: a course's code draws on it


def test_colour_conversions_are_opencvs() -> None:
    rgb = _image((6, 8, 3))
    msg = bridge.cv2_to_imgmsg(rgb, "rgb8")
    assert np.array_equal(bridge.imgmsg_to_cv2(msg, "bgr8"), rgb[:, :, ::-1])
    assert np.array_equal(bridge.imgmsg_to_cv2(msg, "mono8"), cv2.cvtColor(rgb, cv2.COLOR_RGB2GRAY))
    bgra = bridge.imgmsg_to_cv2(msg, "bgra8")
    assert bgra.shape == (6, 8, 4) and np.all(bgra[:, :, 3] == 255)
    assert np.array_equal(bridge.imgmsg_to_cv2(msg, "rgb8"), rgb)  # the same encoding: a copy


def test_bit_depth_changes_scale_to_the_full_range() -> None:
    grey = np.array([[0, 1, 128, 255]], dtype=np.uint8)
    wide = bridge.imgmsg_to_cv2(bridge.cv2_to_imgmsg(grey, "mono8"), "mono16")
    assert wide.dtype == np.uint16 and wide.tolist() == [[0, 257, 32896, 65535]]
    narrow = bridge.imgmsg_to_cv2(bridge.cv2_to_imgmsg(np.array([[0, 256, 32896, 65535]], dtype=np.uint16), "mono16"), "mono8")
    assert narrow.tolist() == [[0, 1, 128, 255]]
    colour = bridge.imgmsg_to_cv2(bridge.cv2_to_imgmsg(np.array([[65535]], dtype=np.uint16), "mono16"), "bgr8")
    assert colour.dtype == np.uint8 and colour.tolist() == [[[255, 255, 255]]]  # grey to colour, then depth


def test_rows_with_padding_and_big_endian_data_are_read_right() -> None:
    values = np.array([[1, 2, 3], [4, 5, 6]], dtype=">u2")
    padded = b"".join(row.tobytes() + b"\xff\xff" for row in values)  # 2 bytes of padding per row
    msg = Image(height=2, width=3, encoding="mono16", is_bigendian=1, step=8, data=padded)
    image = bridge.imgmsg_to_cv2(msg)
    assert image.dtype == np.uint16 and image.dtype.isnative and image.tolist() == [[1, 2, 3], [4, 5, 6]]
    swapped = bridge.cv2_to_imgmsg(values, "mono16")
    assert swapped.is_bigendian == 1 and bridge.imgmsg_to_cv2(swapped).tolist() == [[1, 2, 3], [4, 5, 6]]


def test_bayer_and_yuv_cameras_convert_to_colour() -> None:
    bayer = _image((4, 6))
    colour = bridge.imgmsg_to_cv2(Image(height=4, width=6, encoding="bayer_rggb8", step=6, data=bayer.tobytes()), "bgr8")
    assert np.array_equal(colour, cv2.cvtColor(bayer, cv2.COLOR_BayerBG2BGR))  # OpenCV's name for RGGB
    uyvy = _image((2, 4, 2))
    rgb = bridge.imgmsg_to_cv2(Image(height=2, width=4, encoding="yuv422", step=8, data=uyvy.tobytes()), "rgb8")
    assert np.array_equal(rgb, cv2.cvtColor(uyvy, cv2.COLOR_YUV2RGB_UYVY))
    assert all(hasattr(cv2, code) for code in _CODES.values())  # every conversion named is OpenCV's


def test_compressed_images_there_and_back() -> None:
    image = np.zeros((32, 48, 3), dtype=np.uint8)
    image[:, :24] = (255, 0, 0)  # blue on the left, in BGR
    png = bridge.cv2_to_compressed_imgmsg(image, dst_format="png")
    assert isinstance(png, CompressedImage) and png.format == "png" and png.data.startswith(b"\x89PNG")
    assert np.array_equal(bridge.compressed_imgmsg_to_cv2(png), image)
    jpeg = bridge.cv2_to_compressed_imgmsg(image)
    assert jpeg.format == "jpg" and jpeg.data.startswith(b"\xff\xd8")
    rgb = bridge.compressed_imgmsg_to_cv2(jpeg, "rgb8")
    assert np.abs(rgb.astype(int) - image[:, :, ::-1]).mean() < 3  # lossy, but the same picture
    grey = bridge.compressed_imgmsg_to_cv2(bridge.cv2_to_compressed_imgmsg(image[:, :, 0], "png"), "bgr8")
    assert grey.shape == (32, 48, 3)


@pytest.mark.parametrize(
    ("call", "message"),
    [
        (lambda: bridge.imgmsg_to_cv2(Image(height=1, width=1, encoding="rgb9", step=3, data=b"abc")), r"^Unrecognized image encoding \[rgb9\]$"),
        (lambda: bridge.cv2_to_imgmsg(np.zeros((2, 2), np.uint8), "bgr8"), r"^encoding specified as bgr8, but image has incompatible type 8UC1$"),
        (lambda: bridge.imgmsg_to_cv2(bridge.cv2_to_imgmsg(np.zeros((2, 2), np.float32)), "bgr8"), r"^\[32FC1\] is not a color format. but \[bgr8\] is"),
        (lambda: bridge.imgmsg_to_cv2(bridge.cv2_to_imgmsg(np.zeros((2, 2, 3), np.uint8), "bgr8"), "yuv422"), r"^Unsupported conversion from \[bgr8\] to \[yuv422\]$"),
        (lambda: bridge.imgmsg_to_cv2(Image(height=4, width=4, encoding="rgb8", step=12, data=b"\0" * 10)), "the image's data does not fit its size: 4x4 rgb8 needs rows of 12 bytes"),
        (lambda: bridge.cv2_to_imgmsg(np.zeros((2, 2), np.int64)), "numpy type int64 has no OpenCV type"),
        (lambda: bridge.compressed_imgmsg_to_cv2(CompressedImage(format="jpeg", data=b"not a jpeg")), r"could not decode the compressed image \(10 bytes, format 'jpeg'\)"),
        (lambda: bridge.cv2_to_compressed_imgmsg(np.zeros((2, 2), np.uint8), "nope"), "could not encode the image as 'nope'"),
    ],
)  # fmt: skip
def test_errors_say_what_is_wrong(call, message: str) -> None:  # type: ignore[no-untyped-def]
    with pytest.raises(CvBridgeError, match=message) as raised:
        call()
    assert isinstance(raised.value, TypeError) and isinstance(raised.value, SkydeckError)


def test_not_an_array_is_a_type_error_as_in_ros() -> None:
    with pytest.raises(TypeError, match="Your input type is not a numpy array"):
        bridge.cv2_to_imgmsg([[1, 2], [3, 4]])
    assert getCvType("bgr8") == cv2.CV_8UC3 and getCvType("32FC1") == cv2.CV_32FC1
