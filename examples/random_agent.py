"""The README's Python quickstart as a script: random actions on HyQ-v0, one episode.

    python examples/random_agent.py
"""

import gymnasium as gym

import hyq  # noqa: F401  (registers HyQ-v0)

env = gym.make("HyQ-v0")
obs, info = env.reset(seed=0)
episode_return, done = 0.0, False
while not done:
    obs, reward, terminated, truncated, info = env.step(env.action_space.sample())
    episode_return += reward
    done = terminated or truncated
print(f"t = {info['t']}, return = {episode_return:.3f}, ended by {info['reasons']}")
