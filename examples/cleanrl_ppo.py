#!/usr/bin/env python3
"""Continuous-action PPO written the way CleanRL's single-file scripts are, against Gymnasium's vector API only:
the environment comes from gymnasium.make_vec by its id, Gymnasium's own vector wrappers normalise it, and the
agent reads single_observation_space and single_action_space. Nothing here knows peg3d but the id and its
keyword arguments (docs/python.md, "Gymnasium").

    .venv/bin/python examples/cleanrl_ppo.py --env-id peg3d/Pursuer-v0 --total-timesteps 1000000 \
        --env-kwargs '{"map": "maps/paper.yaml", "opponent": "flee", "threads": 2}' --log curve.csv

Gymnasium 1.x autoresets on the next step: the step after an episode's end only resets that game, so it is
no transition and is left out of the loss.
"""

import argparse
import csv
import json
import math
import time

import gymnasium as gym
import numpy as np
import torch
from torch import nn

import peg3d  # noqa: F401 - registers the environment ids


def layer(inputs, outputs, std=math.sqrt(2)):
    lin = nn.Linear(inputs, outputs)
    nn.init.orthogonal_(lin.weight, std)
    nn.init.zeros_(lin.bias)
    return lin


class Agent(nn.Module):
    def __init__(self, n_obs, n_act):
        super().__init__()
        self.critic = nn.Sequential(layer(n_obs, 64), nn.Tanh(), layer(64, 64), nn.Tanh(), layer(64, 1, 1.0))
        self.actor_mean = nn.Sequential(layer(n_obs, 64), nn.Tanh(), layer(64, 64), nn.Tanh(), layer(64, n_act, 0.01))
        self.actor_logstd = nn.Parameter(torch.zeros(1, n_act))

    def value(self, x):
        return self.critic(x).squeeze(-1)

    def act(self, x, action=None):
        mean = self.actor_mean(x)
        dist = torch.distributions.Normal(mean, self.actor_logstd.expand_as(mean).exp())
        if action is None:
            action = dist.sample()
        return action, dist.log_prob(action).sum(-1), dist.entropy().sum(-1), self.value(x)


def make_envs(args):
    envs = gym.make_vec(args.env_id, num_envs=args.num_envs, vectorization_mode="vector_entry_point",
                        **json.loads(args.env_kwargs))
    envs = gym.wrappers.vector.RecordEpisodeStatistics(envs)
    envs = gym.wrappers.vector.ClipAction(envs)
    envs = gym.wrappers.vector.NormalizeObservation(envs)
    envs = gym.wrappers.vector.TransformObservation(envs, lambda o: np.clip(o, -10, 10))
    envs = gym.wrappers.vector.NormalizeReward(envs, gamma=args.gamma)
    envs = gym.wrappers.vector.TransformReward(envs, lambda r: np.clip(r, -10, 10))
    return envs


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--env-id", default="peg3d/Pursuer-v0")
    ap.add_argument("--env-kwargs", default="{}", help="keyword arguments of the environment, as JSON")
    ap.add_argument("--total-timesteps", type=int, default=1_000_000)
    ap.add_argument("--num-envs", type=int, default=16)
    ap.add_argument("--num-steps", type=int, default=256, help="steps per game per rollout")
    ap.add_argument("--learning-rate", type=float, default=3e-4)
    ap.add_argument("--gamma", type=float, default=0.99)
    ap.add_argument("--gae-lambda", type=float, default=0.95)
    ap.add_argument("--num-minibatches", type=int, default=32)
    ap.add_argument("--update-epochs", type=int, default=10)
    ap.add_argument("--clip-coef", type=float, default=0.2)
    ap.add_argument("--ent-coef", type=float, default=0.0)
    ap.add_argument("--vf-coef", type=float, default=0.5)
    ap.add_argument("--max-grad-norm", type=float, default=0.5)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--log", help="CSV of the learning curve: env steps, mean episodic return, episodes")
    args = ap.parse_args()
    torch.manual_seed(args.seed)
    torch.set_num_threads(1)
    envs = make_envs(args)
    n_obs = int(np.prod(envs.single_observation_space.shape))
    n_act = int(np.prod(envs.single_action_space.shape))
    agent = Agent(n_obs, n_act)
    optimizer = torch.optim.Adam(agent.parameters(), lr=args.learning_rate, eps=1e-5)
    N, T = args.num_envs, args.num_steps
    obs = torch.zeros((T, N, n_obs))
    actions = torch.zeros((T, N, n_act))
    logprobs, rewards, dones, values, valid = (torch.zeros((T, N)) for _ in range(5))
    batch_size = N * T
    minibatch = batch_size // args.num_minibatches
    updates = max(1, args.total_timesteps // batch_size)
    next_obs, _ = envs.reset(seed=[args.seed * 1000 + i for i in range(N)])
    next_obs = torch.as_tensor(next_obs, dtype=torch.float32)
    next_done = torch.zeros(N)
    resetting = np.zeros(N, dtype=bool)  # the games whose next step only resets them
    curve, returns, step, start = [], [], 0, time.time()
    log = open(args.log, "w", newline="") if args.log else None
    writer = csv.writer(log) if log else None
    if writer:
        writer.writerow(["env_steps", "mean_return", "episodes", "seconds"])
    for update in range(1, updates + 1):
        for g in optimizer.param_groups:
            g["lr"] = args.learning_rate * (1.0 - (update - 1.0) / updates)
        for t in range(T):
            step += N
            obs[t], dones[t] = next_obs, next_done
            valid[t] = torch.as_tensor(~resetting, dtype=torch.float32)
            with torch.no_grad():
                action, logprob, _, value = agent.act(next_obs)
            values[t], actions[t], logprobs[t] = value, action, logprob
            o, r, term, trunc, info = envs.step(action.numpy())
            done = np.logical_or(term, trunc)
            rewards[t] = torch.as_tensor(r, dtype=torch.float32)
            next_obs = torch.as_tensor(o, dtype=torch.float32)
            next_done = torch.as_tensor(done, dtype=torch.float32)
            resetting = done
            if "episode" in info:
                returns += [float(x) for x in info["episode"]["r"][info["_episode"]]]
        with torch.no_grad():
            next_value = agent.value(next_obs)
            advantages = torch.zeros((T, N))
            gae = torch.zeros(N)
            for t in reversed(range(T)):
                if t == T - 1:
                    nonterminal, later = 1.0 - next_done, next_value
                else:
                    nonterminal, later = 1.0 - dones[t + 1], values[t + 1]
                # A reset step carries nothing over: the transition before it ended its episode.
                delta = rewards[t] + args.gamma * later * nonterminal - values[t]
                gae = delta + args.gamma * args.gae_lambda * nonterminal * gae
                gae = gae * valid[t]
                advantages[t] = gae
            targets = advantages + values
        keep = valid.reshape(-1) > 0
        b_obs, b_act = obs.reshape(-1, n_obs)[keep], actions.reshape(-1, n_act)[keep]
        b_logp, b_adv, b_ret = logprobs.reshape(-1)[keep], advantages.reshape(-1)[keep], targets.reshape(-1)[keep]
        n = b_obs.shape[0]
        for _ in range(args.update_epochs):
            order = torch.randperm(n)
            for lo in range(0, n, minibatch):
                idx = order[lo:lo + minibatch]
                _, newlogp, entropy, newvalue = agent.act(b_obs[idx], b_act[idx])
                ratio = (newlogp - b_logp[idx]).exp()
                adv = b_adv[idx]
                adv = (adv - adv.mean()) / (adv.std() + 1e-8)
                pg_loss = torch.max(-adv * ratio, -adv * ratio.clamp(1 - args.clip_coef, 1 + args.clip_coef)).mean()
                v_loss = 0.5 * ((newvalue - b_ret[idx]) ** 2).mean()
                loss = pg_loss - args.ent_coef * entropy.mean() + args.vf_coef * v_loss
                optimizer.zero_grad()
                loss.backward()
                nn.utils.clip_grad_norm_(agent.parameters(), args.max_grad_norm)
                optimizer.step()
        recent = returns[-100:]
        mean_return = float(np.mean(recent)) if recent else float("nan")
        curve.append((step, mean_return))
        if writer:
            writer.writerow([step, f"{mean_return:.3f}", len(returns), f"{time.time() - start:.1f}"])
            log.flush()
        print(json.dumps({"env_steps": step, "mean_return": mean_return, "episodes": len(returns),
                          "loss": float(loss), "seconds": round(time.time() - start, 1)}), flush=True)
    envs.close()
    if log:
        log.close()


if __name__ == "__main__":
    main()
