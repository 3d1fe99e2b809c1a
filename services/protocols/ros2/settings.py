"""ROS 2's own variables, as the bridge reads them (rclpy reads them too, for its participant)."""

from __future__ import annotations

from pydantic import Field
from pydantic_settings import BaseSettings, SettingsConfigDict

__all__ = ["MAX_DOMAIN", "Ros2Settings"]

MAX_DOMAIN = 232  # ROS 2's highest domain id (Fast DDS's UDP ports run out above it)


class Ros2Settings(BaseSettings):
    """``ROS_DOMAIN_ID`` (the bridge's default domain), and the discovery settings the bridge's
    start-up line reports (``ROS_AUTOMATIC_DISCOVERY_RANGE``, ``ROS_STATIC_PEERS``)."""

    model_config = SettingsConfigDict(extra="ignore")

    domain_id: int = Field(default=0, ge=0, le=MAX_DOMAIN, validation_alias="ROS_DOMAIN_ID")
    discovery_range: str = Field(default="SUBNET", validation_alias="ROS_AUTOMATIC_DISCOVERY_RANGE")
    static_peers: str = Field(default="", validation_alias="ROS_STATIC_PEERS")

    def discovery(self) -> str:
        """How discovery is set, for the start-up line."""
        return f"discovery {self.discovery_range.lower()}" + (f", peers {self.static_peers}" if self.static_peers else "")
