"""Recording and playback (rosbag / ros2 bag) on MCAP files: JSON messages with their schemas.

    from services.bag import BagReader, format_info
    with BagReader("run.mcap") as bag:
        print(format_info(bag.summary))

- :mod:`.writer`: ``BagWriter``, frames into an MCAP file as received (serialised once)
- :mod:`.mcap_file`: ``McapFile``, the records of an MCAP file, written at a recorder's pace
- :mod:`.reader`: ``BagReader``, the summary and the messages, also of a file cut short
- :mod:`.recording`: which topics a recorder picks, and writing their frames
- :mod:`.recorder`: ``Recorder``, the node behind ``skydeck bag record``
- :mod:`.player`: ``Player``, the node behind ``skydeck bag play``
- :mod:`.info`: ``bag info``'s text

The exports load lazily: ``bag info`` reads a file without loading the node SDK.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from shared_models.lazy import lazy_exports

if TYPE_CHECKING:
    from services.bag.errors import BagError, BagFileError
    from services.bag.info import format_info, format_size
    from services.bag.player import Player, PlayOptions, check_types
    from services.bag.reader import BagMessage, BagReader, BagSummary, TopicSummary
    from services.bag.recorder import Recorder
    from services.bag.recording import Limits, Recording, TopicSelection
    from services.bag.writer import BagWriter, bag_path

__all__ = [
    "BagError",
    "BagFileError",
    "BagMessage",
    "BagReader",
    "BagSummary",
    "BagWriter",
    "Limits",
    "PlayOptions",
    "Player",
    "Recorder",
    "Recording",
    "TopicSelection",
    "TopicSummary",
    "bag_path",
    "check_types",
    "format_info",
    "format_size",
]

_HOMES = {
    "BagError": "services.bag.errors",
    "BagFileError": "services.bag.errors",
    "BagMessage": "services.bag.reader",
    "BagReader": "services.bag.reader",
    "BagSummary": "services.bag.reader",
    "BagWriter": "services.bag.writer",
    "Limits": "services.bag.recording",
    "PlayOptions": "services.bag.player",
    "Player": "services.bag.player",
    "Recorder": "services.bag.recorder",
    "Recording": "services.bag.recording",
    "TopicSelection": "services.bag.recording",
    "TopicSummary": "services.bag.reader",
    "bag_path": "services.bag.writer",
    "check_types": "services.bag.player",
    "format_info": "services.bag.info",
    "format_size": "services.bag.info",
}

__getattr__ = lazy_exports(__name__, _HOMES)
