"""Draws a hand-made plan with the simulated arm and writes a picture.

MUJOCO_GL=egl python examples/robot_picture.py --out results/robot.png --video results/robot.mp4
"""

from jdraw.robot import picture

if __name__ == "__main__":
    picture.main()
