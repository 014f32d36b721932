"""The robot's body control: mink IK, gripper, the target field, motion primitives for AEL actions."""
