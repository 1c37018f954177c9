"""CHASM-AUV vehicle simulator: 6-DOF dynamics, sensors, environment, HIL loop."""
