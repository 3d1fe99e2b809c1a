"""The topic edge: where frames enter and leave topics over WebSockets.

- :mod:`.topic_socket`: ``serve_topic_socket`` and the ``TopicPort`` every socket talks to
- :mod:`.options`: ``?queue=&rate=&mode=``
- :mod:`.encoding`: JSON text or msgpack, negotiated per connection; each made once per message
- :mod:`.frames`: refusing a frame with a close code
- :mod:`.pump`: the loop that writes an outbox to a socket and reads what the client sends
- :mod:`.outbox`: a reader's bounded queue (oldest dropped: ROS's queue_size)
- :mod:`.links`: the other direction, a subscriber's connection to a remote publisher
"""

from services.runtime.edge.encoding import Encoding, Frames, decode, encode
from services.runtime.edge.frames import FrameRejected, close_with
from services.runtime.edge.links import PublisherLink, stream_url
from services.runtime.edge.options import Mode, StreamOptions
from services.runtime.edge.outbox import Outbox
from services.runtime.edge.topic_socket import TopicConnection, TopicPort, serve_topic_socket

__all__ = [
    "Encoding",
    "FrameRejected",
    "Frames",
    "Mode",
    "Outbox",
    "PublisherLink",
    "StreamOptions",
    "TopicConnection",
    "TopicPort",
    "close_with",
    "decode",
    "encode",
    "serve_topic_socket",
    "stream_url",
]
