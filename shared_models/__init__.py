"""Typed ROS messages and service types for Skydeck (pydantic v2), and ROS-style names."""

from shared_models._message import Message, ServiceType, all_interfaces

__all__ = ["Message", "ServiceType", "all_interfaces"]
