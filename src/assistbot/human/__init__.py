"""The scripted human partner: arm control, behaviours, profiles, reactions to the robot."""
