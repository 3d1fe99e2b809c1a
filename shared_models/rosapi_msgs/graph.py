"""rosapi_msgs' view of the graph: topics, services, nodes, and message types (``TypeDef``)."""

from __future__ import annotations

from pydantic import Field

from shared_models._message import Int32, Message, ServiceType, String


class TypeDef(Message):
    """One message type's fields, as rosapi describes them (roslibjs rebuilds messages from it)."""

    __ros_type__ = "rosapi_msgs/msg/TypeDef"

    type: String = ""
    fieldnames: list[String] = Field(default_factory=list)
    fieldtypes: list[String] = Field(default_factory=list)
    fieldarraylen: list[Int32] = Field(default_factory=list)  # -1: not an array, 0: any length
    examples: list[String] = Field(default_factory=list)
    constnames: list[String] = Field(default_factory=list)
    constvalues: list[String] = Field(default_factory=list)


# -- topics ---------------------------------------------------------------------------------------


class TopicsRequest(Message):
    __ros_type__ = "rosapi_msgs/srv/Topics_Request"


class TopicsResponse(Message):
    __ros_type__ = "rosapi_msgs/srv/Topics_Response"

    topics: list[String] = Field(default_factory=list)
    types: list[String] = Field(default_factory=list)


class TopicsForTypeRequest(Message):
    __ros_type__ = "rosapi_msgs/srv/TopicsForType_Request"

    type: String = ""


class TopicsForTypeResponse(Message):
    __ros_type__ = "rosapi_msgs/srv/TopicsForType_Response"

    topics: list[String] = Field(default_factory=list)


class TopicTypeRequest(Message):
    __ros_type__ = "rosapi_msgs/srv/TopicType_Request"

    topic: String = ""


class TopicTypeResponse(Message):
    __ros_type__ = "rosapi_msgs/srv/TopicType_Response"

    type: String = ""


class PublishersRequest(Message):
    __ros_type__ = "rosapi_msgs/srv/Publishers_Request"

    topic: String = ""


class PublishersResponse(Message):
    __ros_type__ = "rosapi_msgs/srv/Publishers_Response"

    publishers: list[String] = Field(default_factory=list)


class SubscribersRequest(Message):
    __ros_type__ = "rosapi_msgs/srv/Subscribers_Request"

    topic: String = ""


class SubscribersResponse(Message):
    __ros_type__ = "rosapi_msgs/srv/Subscribers_Response"

    subscribers: list[String] = Field(default_factory=list)


class Topics(ServiceType):
    """Every topic and its type."""

    __ros_type__ = "rosapi_msgs/srv/Topics"
    Request = TopicsRequest
    Response = TopicsResponse


class TopicsForType(ServiceType):
    """The topics of one message type."""

    __ros_type__ = "rosapi_msgs/srv/TopicsForType"
    Request = TopicsForTypeRequest
    Response = TopicsForTypeResponse


class TopicType(ServiceType):
    """The type of one topic."""

    __ros_type__ = "rosapi_msgs/srv/TopicType"
    Request = TopicTypeRequest
    Response = TopicTypeResponse


class Publishers(ServiceType):
    """The nodes publishing one topic."""

    __ros_type__ = "rosapi_msgs/srv/Publishers"
    Request = PublishersRequest
    Response = PublishersResponse


class Subscribers(ServiceType):
    """The nodes subscribed to one topic."""

    __ros_type__ = "rosapi_msgs/srv/Subscribers"
    Request = SubscribersRequest
    Response = SubscribersResponse


# -- services -------------------------------------------------------------------------------------


class ServicesRequest(Message):
    __ros_type__ = "rosapi_msgs/srv/Services_Request"


class ServicesResponse(Message):
    __ros_type__ = "rosapi_msgs/srv/Services_Response"

    services: list[String] = Field(default_factory=list)


class ServicesForTypeRequest(Message):
    __ros_type__ = "rosapi_msgs/srv/ServicesForType_Request"

    type: String = ""


class ServicesForTypeResponse(Message):
    __ros_type__ = "rosapi_msgs/srv/ServicesForType_Response"

    services: list[String] = Field(default_factory=list)


class ServiceTypeRequest(Message):
    __ros_type__ = "rosapi_msgs/srv/ServiceType_Request"

    service: String = ""


class ServiceTypeResponse(Message):
    __ros_type__ = "rosapi_msgs/srv/ServiceType_Response"

    type: String = ""


class ServiceNodeRequest(Message):
    __ros_type__ = "rosapi_msgs/srv/ServiceNode_Request"

    service: String = ""


class ServiceNodeResponse(Message):
    __ros_type__ = "rosapi_msgs/srv/ServiceNode_Response"

    node: String = ""


class ServiceProvidersRequest(Message):
    __ros_type__ = "rosapi_msgs/srv/ServiceProviders_Request"

    service: String = ""


class ServiceProvidersResponse(Message):
    __ros_type__ = "rosapi_msgs/srv/ServiceProviders_Response"

    providers: list[String] = Field(default_factory=list)


class Services(ServiceType):
    """Every service."""

    __ros_type__ = "rosapi_msgs/srv/Services"
    Request = ServicesRequest
    Response = ServicesResponse


class ServicesForType(ServiceType):
    """The services of one service type."""

    __ros_type__ = "rosapi_msgs/srv/ServicesForType"
    Request = ServicesForTypeRequest
    Response = ServicesForTypeResponse


class ServiceType_(ServiceType):  # "ServiceType" is the base class of every service type
    """The type of one service."""

    __ros_type__ = "rosapi_msgs/srv/ServiceType"
    Request = ServiceTypeRequest
    Response = ServiceTypeResponse


class ServiceNode(ServiceType):
    """The node hosting one service."""

    __ros_type__ = "rosapi_msgs/srv/ServiceNode"
    Request = ServiceNodeRequest
    Response = ServiceNodeResponse


class ServiceProviders(ServiceType):
    """The nodes hosting one service."""

    __ros_type__ = "rosapi_msgs/srv/ServiceProviders"
    Request = ServiceProvidersRequest
    Response = ServiceProvidersResponse


# -- nodes ----------------------------------------------------------------------------------------


class NodesRequest(Message):
    __ros_type__ = "rosapi_msgs/srv/Nodes_Request"


class NodesResponse(Message):
    __ros_type__ = "rosapi_msgs/srv/Nodes_Response"

    nodes: list[String] = Field(default_factory=list)


class NodeDetailsRequest(Message):
    __ros_type__ = "rosapi_msgs/srv/NodeDetails_Request"

    node: String = ""


class NodeDetailsResponse(Message):
    __ros_type__ = "rosapi_msgs/srv/NodeDetails_Response"

    subscribing: list[String] = Field(default_factory=list)
    publishing: list[String] = Field(default_factory=list)
    services: list[String] = Field(default_factory=list)


class Nodes(ServiceType):
    """Every node."""

    __ros_type__ = "rosapi_msgs/srv/Nodes"
    Request = NodesRequest
    Response = NodesResponse


class NodeDetails(ServiceType):
    """What one node subscribes to, publishes and serves."""

    __ros_type__ = "rosapi_msgs/srv/NodeDetails"
    Request = NodeDetailsRequest
    Response = NodeDetailsResponse


# -- types ----------------------------------------------------------------------------------------


class MessageDetailsRequest(Message):
    __ros_type__ = "rosapi_msgs/srv/MessageDetails_Request"

    type: String = ""


class MessageDetailsResponse(Message):
    __ros_type__ = "rosapi_msgs/srv/MessageDetails_Response"

    typedefs: list[TypeDef] = Field(default_factory=list)


class ServiceRequestDetailsRequest(Message):
    __ros_type__ = "rosapi_msgs/srv/ServiceRequestDetails_Request"

    type: String = ""


class ServiceRequestDetailsResponse(Message):
    __ros_type__ = "rosapi_msgs/srv/ServiceRequestDetails_Response"

    typedefs: list[TypeDef] = Field(default_factory=list)


class ServiceResponseDetailsRequest(Message):
    __ros_type__ = "rosapi_msgs/srv/ServiceResponseDetails_Request"

    type: String = ""


class ServiceResponseDetailsResponse(Message):
    __ros_type__ = "rosapi_msgs/srv/ServiceResponseDetails_Response"

    typedefs: list[TypeDef] = Field(default_factory=list)


class MessageDetails(ServiceType):
    """A message type and every type inside it."""

    __ros_type__ = "rosapi_msgs/srv/MessageDetails"
    Request = MessageDetailsRequest
    Response = MessageDetailsResponse


class ServiceRequestDetails(ServiceType):
    """A service's request type and every type inside it."""

    __ros_type__ = "rosapi_msgs/srv/ServiceRequestDetails"
    Request = ServiceRequestDetailsRequest
    Response = ServiceRequestDetailsResponse


class ServiceResponseDetails(ServiceType):
    """A service's response type and every type inside it."""

    __ros_type__ = "rosapi_msgs/srv/ServiceResponseDetails"
    Request = ServiceResponseDetailsRequest
    Response = ServiceResponseDetailsResponse


class ServiceHostRequest(Message):
    __ros_type__ = "rosapi_msgs/srv/ServiceHost_Request"

    service: String = ""


class ServiceHostResponse(Message):
    __ros_type__ = "rosapi_msgs/srv/ServiceHost_Response"

    host: String = ""


class ServiceHost(ServiceType):
    """The host of the node serving one service (ROS 1's rosapi)."""

    __ros_type__ = "rosapi_msgs/srv/ServiceHost"
    Request = ServiceHostRequest
    Response = ServiceHostResponse


class TopicsAndRawTypesRequest(Message):
    __ros_type__ = "rosapi_msgs/srv/TopicsAndRawTypes_Request"


class TopicsAndRawTypesResponse(Message):
    __ros_type__ = "rosapi_msgs/srv/TopicsAndRawTypes_Response"

    topics: list[String] = Field(default_factory=list)
    types: list[String] = Field(default_factory=list)
    typedefs_full_text: list[String] = Field(default_factory=list)  # each type's definition and those it uses


class TopicsAndRawTypes(ServiceType):
    """Every topic, its type and its full definition text (what ``cbor-raw`` readers parse with)."""

    __ros_type__ = "rosapi_msgs/srv/TopicsAndRawTypes"
    Request = TopicsAndRawTypesRequest
    Response = TopicsAndRawTypesResponse
