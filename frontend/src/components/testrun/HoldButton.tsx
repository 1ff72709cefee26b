import { Button } from "@mantine/core";
import type { KeyboardEvent, PointerEvent, ReactNode } from "react";
import { useReadOnly } from "../../hooks/useControl";

interface HoldButtonProps {
  onPress: () => void;
  onRelease: () => void;
  held: boolean;
  disabled?: boolean;
  testId: string;
  children: ReactNode;
  leftSection?: ReactNode;
  label: string;
}

const HOLD_KEYS = new Set([" ", "Enter"]);

/**
 * A dead-man button: active only while held with the primary pointer button, or with Space/Enter while focused.
 * Releasing, leaving the button, a cancelled pointer and losing the focus all release it.
 */
export function HoldButton({ onPress, onRelease, held, disabled: off, testId, children, leftSection, label }: HoldButtonProps) {
  const disabled = off || useReadOnly(); // another client holds test-run control
  const down = (e: PointerEvent<HTMLButtonElement>) => {
    if (e.button !== 0 || disabled) return;
    onPress();
  };
  const keyDown = (e: KeyboardEvent<HTMLButtonElement>) => {
    if (!HOLD_KEYS.has(e.key)) return;
    e.preventDefault();
    if (!e.repeat && !disabled) onPress();
  };
  const keyUp = (e: KeyboardEvent<HTMLButtonElement>) => {
    if (!HOLD_KEYS.has(e.key)) return;
    e.preventDefault();
    onRelease();
  };
  return (
    <Button
      className="jog-button"
      data-testid={testId}
      data-held={held ? "true" : "false"}
      aria-pressed={held}
      aria-label={label}
      variant={held ? "filled" : "light"}
      color="blue"
      disabled={disabled}
      leftSection={leftSection}
      onPointerDown={down}
      onPointerUp={onRelease}
      onPointerLeave={onRelease}
      onPointerCancel={onRelease}
      onLostPointerCapture={onRelease}
      onKeyDown={keyDown}
      onKeyUp={keyUp}
      onBlur={onRelease}
      onContextMenu={(e) => e.preventDefault()}
      miw={84}
    >
      {children}
    </Button>
  );
}
