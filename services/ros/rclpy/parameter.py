"""``rclpy.parameter``: ``Parameter('speed', Parameter.Type.DOUBLE, 0.5)``, the SDK's own class
(one parameter type for every node, so ``skydeck param`` sees these too)."""

from __future__ import annotations

from services.runtime.parameter import Parameter, ParameterValueType, parameter_value_to_python

__all__ = ["Parameter", "ParameterValueType", "parameter_value_to_python"]
