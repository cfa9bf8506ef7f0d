"""
What each simulator does with a robot: the shared vocabulary (engine names, verdicts, events),
fixed-joint lumping, and one model per engine (mujoco, gazebo, drake, pybullet, kdl) whose
events the rules IN070–IN074 turn into findings.
"""
