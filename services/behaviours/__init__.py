"""The robot world's behaviours, each a node ``skydeck run NAME`` knows (the second seed's class):

| name | module | what it does |
|---|---|---|
| ``teleop`` | :mod:`.teleop` | drive from the terminal's keyboard (teleop_twist_keyboard's keys) |
| ``drive_square`` | :mod:`.drive_square` | one square of ``side`` metres, by odometry |
| ``estop`` | :mod:`.estop` | forward, stopping before anything ahead closer than ``distance`` |
| ``wall_follower`` | :mod:`.wall_follower` | a wall kept on one side at ``distance`` |
| ``person_follower`` | :mod:`.person_follower` | the walking person followed at ``distance``, by laser |
| ``obstacle_avoider`` | :mod:`.obstacle_avoider` | to (``goal_x``, ``goal_y``) around obstacles |
| ``fsm`` | :mod:`.fsm` | squares until something is near, then the wall; state on ``fsm/state`` |

Each is a :class:`~services.behaviours.robot.RobotBehaviour`: tunables are node parameters
(``--ros-args -p NAME:=VALUE``), ``--namespace /robot1`` picks a robot when there are several,
``--use-sim-time`` runs its control loop on the simulator's clock. The logic of each is a small
controller class (``SquareDriver``, ``WallFollower``, ...) that the node wraps, so the ``fsm``
chains the same code the single behaviours run.
"""
